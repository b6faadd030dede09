// SPDX-License-Identifier: GPL-2.0
#include "advee/robotsim/sinks.hpp"

#include <cmath>
#include <cstdio>
#include <fstream>
#include <set>
#include <system_error>

namespace advee::robotsim {

namespace {
// `decimals`: the board's resolution (SRF: cm, IR: 2 mm) needs no more.
std::string metres(const std::optional<double>& m, int decimals) {
  if (!m) return "none";
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.*f", decimals, *m);
  return buf;
}
}  // namespace

Rs485SimSink::Rs485SimSink(Rs485Devices devices, const RobotDescription& desc, Send send)
    : dev_(std::move(devices)), desc_(desc), send_(std::move(send)) {}

void Rs485SimSink::set(const std::string& key, const std::string& command) {
  auto it = last_.find(key);
  if (it != last_.end() && it->second == command) return;
  send_(command);
  last_[key] = command;
}

void Rs485SimSink::publish(const SensorFrame& f) {
  const auto board = [&](int b) { return b == 0 ? dev_.sd1_front : dev_.sd1_rear; };
  for (std::size_t i = 0; i < f.srf_m.size() && i < desc_.srf.sensors.size(); ++i) {
    const auto& s = desc_.srf.sensors[i];
    const std::string key = board(s.board) + " srf " + std::to_string(s.index);
    set(key, "set " + key + " " + metres(f.srf_m[i], 2));
  }
  for (std::size_t i = 0; i < f.ir_m.size() && i < desc_.ir.sensors.size(); ++i) {
    const auto& s = desc_.ir.sensors[i];
    const std::string key = board(s.board) + " ir " + std::to_string(s.index);
    set(key, "set " + key + " " + metres(f.ir_m[i], 3));
  }
  set("ticks", "set " + dev_.so1 + " ticks " + std::to_string(f.ticks[0]) + " " + std::to_string(f.ticks[1]));
  std::set<int> seen;
  for (const auto& b : f.beacons) {
    char buf[96];
    std::snprintf(buf, sizeof buf, " beacon %u %.2f %u", b.id, b.bearing_cdeg / 100.0, b.quality);
    set("beacon " + std::to_string(b.id), "set " + dev_.sbs1 + buf);
    seen.insert(b.id);
  }
  for (auto& [key, cmd] : last_) {
    if (key.rfind("beacon ", 0) != 0) continue;
    const int id = std::stoi(key.substr(7));
    if (seen.count(id) || cmd.ends_with(" none")) continue;
    cmd = "set " + dev_.sbs1 + " beacon " + std::to_string(id) + " none";  // lost from sight
    send_(cmd);
  }
  // The boards latch PAUSE sources until CLEAR_PAUSE_SRC: raise only new ones,
  // the rear bumper on the rear board, everything else on the front board.
  const std::uint8_t rising = f.pause & ~last_pause_;
  if (rising & kPauseRearBumper) send_("set " + dev_.sd1_rear + " pause " + std::to_string(kPauseRearBumper));
  if (const std::uint8_t front = rising & ~kPauseRearBumper)
    send_("set " + dev_.sd1_front + " pause " + std::to_string(front));
  // The PAUSE line is not latched: BR-PSS2 engages it while a source is
  // active; the PSC1 reports every change as a PAUSE event.
  if (!dev_.psc1.empty() && f.pause != last_pause_)
    send_("event " + dev_.psc1 + " pause " + std::to_string(f.pause != 0) + " " + std::to_string(f.pause));
  last_pause_ = f.pause;
}

void Max6615DebugfsSink::publish(const SensorFrame& f) {
  for (std::size_t i = 0; i < f.temperature_c.size(); ++i) {
    const std::string path = dir_ + "/temp" + std::to_string(i + 1);
    std::ofstream out(path);
    out << std::lround(f.temperature_c[i] * 1000) << '\n';
    out.flush();
    if (!out) throw std::system_error(errno, std::generic_category(), "write " + path);
  }
}

}  // namespace advee::robotsim
