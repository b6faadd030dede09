// SPDX-License-Identifier: GPL-2.0
// advee-stack-listen: the whole-stack tests' LCM subscriber. Listens for a
// while to every channel of advee/msgs/channels.hpp (and the simulator's
// SIM_DATA_POSE) and prints one decoded line per message:
//   CHANNEL t=MONOTONIC_S module=SENDER key=value ...
// so that a shell test can count messages per channel and compare values.
#include <lcm/lcm-cpp.hpp>
#include <poll.h>

#include <CLI/CLI.hpp>
#include <chrono>
#include <cstdio>
#include <iostream>
#include <set>
#include <sstream>
#include <string>
#include <vector>

#include "advee/module/signals.hpp"
#include "advee/msgs/channels.hpp"
#include "common/cmd_state_t.hpp"
#include "common/data_module_phase_t.hpp"
#include "common/data_state_t.hpp"
#include "common/error_t.hpp"
#include "lowlevel/cmd_homing_t.hpp"
#include "lowlevel/cmd_motion_t.hpp"
#include "lowlevel/cmd_power_t.hpp"
#include "lowlevel/data_active_beacons_t.hpp"
#include "lowlevel/data_beacons_t.hpp"
#include "lowlevel/data_drives_t.hpp"
#include "lowlevel/data_fans_t.hpp"
#include "lowlevel/data_odo_t.hpp"
#include "lowlevel/data_power_t.hpp"
#include "lowlevel/data_srfs_t.hpp"
#include "lowlevel/data_temperature_t.hpp"
#include "lowlevel/event_stop_t.hpp"
#if __has_include("sim/data_pose_t.hpp")
#include "sim/data_pose_t.hpp"
#define ADVEE_HAVE_SIM_POSE 1
#endif

namespace {

constexpr const char* kSimPose = "SIM_DATA_POSE";

std::string num(double v, const char* fmt = "%.4f") {
  char b[48];
  std::snprintf(b, sizeof b, fmt, v);
  return b;
}

// Spaces inside a value would split the key=value pairs.
std::string word(std::string s) {
  for (char& c : s)
    if (c == ' ') c = '_';
  return s.empty() ? "-" : s;
}

double mono_s() {
  return std::chrono::duration<double>(std::chrono::steady_clock::now().time_since_epoch()).count();
}

template <typename Msg>
bool decode(const lcm::ReceiveBuffer* rb, Msg& m) {
  return m.decode(rb->data, 0, rb->data_size) >= 0;
}

std::string describe(const lcm::ReceiveBuffer* rb, const std::string& ch) {
  std::ostringstream o;
  o << ch << " t=" << num(mono_s(), "%.3f");
  if (common::data_state_t m; ch == "CM_DATA_STATE" && decode(rb, m)) {
    o << " module=" << m.module << " state=" << int(m.state) << " pid=" << m.pid;
  } else if (common::cmd_state_t m; ch == "CM_CMD_STATE" && decode(rb, m)) {
    o << " module=" << m.module << " target=" << m.target << " state=" << int(m.state) << " manual=" << int(m.manual);
  } else if (common::error_t m; ch == "CM_DATA_ERROR" && decode(rb, m)) {
    o << " module=" << m.module << " number=" << m.number << " severity=" << int(m.severity) << " text=" << word(m.text);
  } else if (common::data_module_phase_t m; ch == "CM_DATA_MODULES" && decode(rb, m)) {
    o << " module=" << m.module << " target=" << m.target << " phase=" << int(m.phase) << " pid=" << m.pid
      << " restarts=" << m.restarts;
  } else if (lowlevel::data_srfs_t m; ch == "LL_DATA_SRFS" && decode(rb, m)) {
    o << " module=" << m.module << " srfs=" << m.num_srfs << " irs=" << m.num_irs;
    for (int i = 0; i < m.num_srfs; ++i) o << " srf" << m.srf_id[i] << "=" << num(m.srf_range_m[i], "%.3f");
    for (int i = 0; i < m.num_irs; ++i) o << " ir" << m.ir_id[i] << "=" << num(m.ir_range_m[i], "%.3f");
  } else if (lowlevel::data_odo_t m; ch == "LL_DATA_ODO" && decode(rb, m)) {
    o << " module=" << m.module << " ticks_left=" << m.ticks_left << " ticks_right=" << m.ticks_right
      << " interval=" << num(m.interval_s) << " speed=" << num(m.speed_mps) << " yaw=" << num(m.yaw_rate_radps);
  } else if (lowlevel::data_beacons_t m; ch == "LL_DATA_BEACONS" && decode(rb, m)) {
    o << " module=" << m.module << " count=" << m.count;
    for (int i = 0; i < m.count; ++i) o << " b" << m.id[i] << "=" << num(m.bearing_rad[i]);
  } else if (lowlevel::data_active_beacons_t m; ch == "LL_DATA_ACTIVE_BEACONS" && decode(rb, m)) {
    o << " module=" << m.module << " count=" << m.count << " ids=";
    for (int i = 0; i < m.count; ++i) o << (i ? "," : "") << m.id[i];
  } else if (lowlevel::cmd_motion_t m; ch == "LL_CMD_MOTION" && decode(rb, m)) {
    o << " module=" << m.module << " speed=" << num(m.speed_mps) << " steering=" << num(m.steering_rad);
  } else if (lowlevel::cmd_homing_t m; ch == "LL_CMD_HOMING" && decode(rb, m)) {
    o << " module=" << m.module << " axis=" << int(m.axis);
  } else if (lowlevel::cmd_power_t m; ch == "LL_CMD_POWER" && decode(rb, m)) {
    o << " module=" << m.module << " action=" << int(m.action) << " output=" << int(m.output) << " on=" << int(m.on);
  } else if (lowlevel::data_power_t m; ch == "LL_DATA_POWER" && decode(rb, m)) {
    unsigned mask = 0;
    for (int i = 0; i < m.num_outputs; ++i) mask |= m.on[i] ? 1u << i : 0u;
    o << " module=" << m.module << " outputs=" << m.num_outputs << " mask=" << mask << " paused=" << int(m.paused);
    for (int i = 0; i < m.num_outputs; ++i) o << " i" << i << "=" << num(m.current_a[i], "%.3f");
  } else if (lowlevel::event_stop_t m; ch == "LL_EVENT_STOP" && decode(rb, m)) {
    o << " module=" << m.module << " stop=" << int(m.stop) << " source=" << int(m.source);
  } else if (lowlevel::data_temperature_t m; ch == "LL_DATA_TEMPERATURE" && decode(rb, m)) {
    o << " module=" << m.module << " count=" << m.count;
    for (int i = 0; i < m.count; ++i) o << " " << word(m.label[i]) << "=" << num(m.celsius[i], "%.3f");
  } else if (lowlevel::data_fans_t m; ch == "LL_DATA_FANS" && decode(rb, m)) {
    o << " module=" << m.module << " count=" << m.count << " fan_fail=" << int(m.fan_fail);
    for (int i = 0; i < m.count; ++i) o << " " << word(m.label[i]) << "=" << m.rpm[i];
  } else if (lowlevel::data_drives_t m; ch == "LL_DATA_DRIVES" && decode(rb, m)) {
    o << " module=" << m.module << " drives=" << m.num_drives;
    for (int i = 0; i < m.num_drives; ++i)
      o << " node" << int(m.node[i]) << "=" << word(m.state[i]) << " fault" << int(m.node[i]) << "=" << int(m.fault[i]);
    o << " speed=" << num(m.speed_mps) << " steering=" << num(m.steering_rad) << " cmd_speed=" << num(m.cmd_speed_mps)
      << " cmd_steering=" << num(m.cmd_steering_rad) << " stopped=" << int(m.stopped)
      << " reason=" << word(m.stop_reason);
#ifdef ADVEE_HAVE_SIM_POSE
  } else if (sim::data_pose_t m; ch == kSimPose && decode(rb, m)) {
    o << " module=robot-sim sim_t=" << num(m.sim_time_s, "%.2f") << " x=" << num(m.x_m) << " y=" << num(m.y_m)
      << " heading=" << num(m.heading_rad) << " speed=" << num(m.speed_mps) << " steering=" << num(m.steering_rad)
      << " pause_sources=" << int(m.pause_sources) << " pause=" << int(m.pause_engaged)
      << " ticks_left=" << m.ticks_left << " ticks_right=" << m.ticks_right;
#endif
  } else {
    o << " undecoded bytes=" << rb->data_size;
  }
  return o.str();
}

struct Printer {
  void on(const lcm::ReceiveBuffer* rb, const std::string& ch) { std::cout << describe(rb, ch) << '\n' << std::flush; }
};

}  // namespace

int main(int argc, char** argv) {
  double seconds = 5;
  std::vector<std::string> channels;
  CLI::App app{
      "advee-stack-listen: prints every message of the low level's LCM channels for a while, one decoded line "
      "each: `CHANNEL t=MONOTONIC_SECONDS module=SENDER key=value ...` (the whole-stack VM tests count and "
      "compare them). Without CHANNEL arguments: every channel of advee/msgs/channels.hpp and SIM_DATA_POSE "
      "(robot-sim's ground truth). The LCM URL comes from LCM_DEFAULT_URL.\n\n"
      "Exit status: 0, 1 when LCM does not start, 2 on bad arguments.",
      "advee-stack-listen"};
  app.add_option("-s,--seconds", seconds, "how long to listen")->check(CLI::Range(0.1, 86400.0))->capture_default_str();
  app.add_option("channels", channels, "channels to listen to (default: all)");
  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    const int rc = app.exit(e);
    return rc == 0 ? 0 : 2;
  }
  if (channels.empty()) {
    for (const auto& c : advee::msgs::kAllChannels) channels.emplace_back(c.name);
    channels.emplace_back(kSimPose);
  }
  try {
    advee::module::SignalFd signals({SIGINT, SIGTERM});
    lcm::LCM lcm;
    if (!lcm.good()) {
      std::cerr << "advee-stack-listen: LCM did not start (multicast route? see docs/modules.md)\n";
      return 1;
    }
    Printer printer;
    std::set<std::string> unique(channels.begin(), channels.end());
    for (const auto& c : unique) lcm.subscribe(c, &Printer::on, &printer);
    const auto end = std::chrono::steady_clock::now() + std::chrono::duration<double>(seconds);
    for (;;) {
      const auto left = std::chrono::duration_cast<std::chrono::milliseconds>(end - std::chrono::steady_clock::now());
      if (left.count() <= 0) break;
      pollfd fds[2] = {{lcm.getFileno(), POLLIN, 0}, {signals.fd(), POLLIN, 0}};
      if (::poll(fds, 2, static_cast<int>(left.count())) < 0) {
        if (errno == EINTR) continue;
        throw std::system_error(errno, std::generic_category(), "poll");
      }
      if (fds[1].revents & POLLIN) break;
      if (fds[0].revents & POLLIN) lcm.handle();
    }
    return 0;
  } catch (const std::exception& e) {
    std::cerr << "advee-stack-listen: " << e.what() << "\n";
    return 1;
  }
}
