// SPDX-License-Identifier: GPL-2.0
// rs485-load: the robot's real RS-485 load against advee-rs485-sim - two BR-SD1
// and one BR-SO1 on bus a polled at 4 Hz, one BR-SBS1 on bus b at 1 Hz - for
// a given time. Checks that every poll completes with a reading or a
// protocol outcome (a clear error), that no call takes longer than
// timeout x (retries + 1) + slack, that the readings are the ones the
// simulator was set to, and that the resident memory stays flat.
// Exit status 0 = all held. docs/rs485-sim.md: the soak.
#include <CLI/CLI.hpp>
#include <atomic>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <map>
#include <mutex>
#include <numbers>
#include <string>
#include <thread>

#include "advee/rs485/bus.hpp"
#include "advee/rs485/devices/sbs1.hpp"
#include "advee/rs485/devices/sd1.hpp"
#include "advee/rs485/devices/so1.hpp"
#include "advee/rs485sim/control_client.hpp"

namespace rs = advee::rs485;
using Clock = std::chrono::steady_clock;
using namespace std::chrono_literals;

namespace {

// A "Name:   N kB" line of /proc/self/status (VmRSS, RssAnon), -1 if missing.
long status_kb(const std::string& name) {
  std::ifstream in("/proc/self/status");
  for (std::string line; std::getline(in, line);)
    if (line.rfind(name + ":", 0) == 0) return std::stol(line.substr(name.size() + 1));
  return -1;
}

// VmRSS decides; RssAnon (heap and stacks, without the code pages of the
// libraries that late code paths fault in) tells a leak from those.
struct Rss {
  long vm = -1, anon = -1;
  static Rss now() { return {status_kb("VmRSS"), status_kb("RssAnon")}; }
};

// Counters of one polled device (updated by its bus's polling thread only).
struct DeviceLoad {
  std::string name;
  std::uint64_t polls = 0, ok = 0, wrong_data = 0, unclear = 0;
  std::map<std::string, std::uint64_t> errors;  // by outcome name
  double max_ms = 0;
};

struct Limits {
  double bound_ms;
  std::atomic<std::uint64_t> over_bound{0};
  std::atomic<double> max_ms{0};
};

// Times one call and counts its outcome; `check` judges a value against the
// readings the simulator was set to (false = wrong data).
template <typename Call, typename Check>
void poll_one(DeviceLoad& d, Limits& lim, Call&& call, Check&& check) {
  const auto t0 = Clock::now();
  const auto result = call();
  const double ms = std::chrono::duration<double, std::milli>(Clock::now() - t0).count();
  ++d.polls;
  d.max_ms = std::max(d.max_ms, ms);
  for (double m = lim.max_ms; ms > m && !lim.max_ms.compare_exchange_weak(m, ms);) {
  }
  if (ms > lim.bound_ms) {
    ++lim.over_bound;
    std::fprintf(stderr, "rs485-load: %s: call took %.1f ms (bound %.1f ms)\n", d.name.c_str(), ms, lim.bound_ms);
  }
  if (result) {
    ++d.ok;
    if (!check(*result)) ++d.wrong_data;
    return;
  }
  // A clear error is one of the protocol's outcomes; anything else (EIO, ...) is not.
  const std::error_code ec = result.error();
  if (rs::is_protocol_outcome(ec)) {
    ++d.errors[ec.message()];
  } else {
    ++d.unclear;
    std::fprintf(stderr, "rs485-load: %s: %s\n", d.name.c_str(), ec.message().c_str());
  }
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app(
      "rs485-load - poll simulated RS-485 boards at the robot's rates and check every call\n\n"
      "Bus a: BR-SD1 at --sd1 (two), BR-SO1 at --so1, every 250 ms (4 Hz); bus b: BR-SBS1 at\n"
      "--sbs1 every second. With --control, sets the simulator's readings first and then\n"
      "checks every reading it gets against them. Runs advee-rs485-sim first (see docs/rs485-sim.md).",
      "rs485-load");
  std::string bus_a = "/dev/ttyTSU0", bus_b = "/dev/ttyTSU1", control;
  std::vector<std::string> sd1_addr{"0x10", "0x11"};
  std::string so1_addr = "0x20", sbs1_addr = "0x30";
  double seconds = 60, slack_ms = 250;
  unsigned timeout_ms = 100, retries = 2;
  long rss_slack_kb = 512;
  app.add_option("--bus-a", bus_a, "tty of bus a (SD1, SO1)")->capture_default_str();
  app.add_option("--bus-b", bus_b, "tty of bus b (SBS1)")->capture_default_str();
  app.add_option("--control", control, "advee-rs485-sim control socket: set readings, check them");
  app.add_option("--sd1", sd1_addr, "addresses of the two SD1")->expected(2)->capture_default_str();
  app.add_option("--so1", so1_addr, "address of the SO1")->capture_default_str();
  app.add_option("--sbs1", sbs1_addr, "address of the SBS1")->capture_default_str();
  app.add_option("-t,--seconds", seconds, "how long to poll")->capture_default_str();
  app.add_option("--timeout-ms", timeout_ms, "response timeout of every call")->capture_default_str();
  app.add_option("--retries", retries, "retries of every call")->capture_default_str();
  app.add_option("--slack-ms", slack_ms, "allowed over timeout x (retries + 1) per call")->capture_default_str();
  app.add_option("--rss-slack-kb", rss_slack_kb, "allowed VmRSS growth from start to end")->capture_default_str();
  app.footer("EXIT STATUS: 0 every check held, 1 a check failed, 2 bad arguments or set-up.");
  CLI11_PARSE(app, argc, argv);

  const auto addr = [](const std::string& s) { return static_cast<std::uint8_t>(std::stoul(s, nullptr, 0)); };
  Limits lim;
  lim.bound_ms = double(timeout_ms) * (retries + 1) + slack_ms;
  std::vector<DeviceLoad> load(4);
  std::uint64_t overruns_a = 0, overruns_b = 0;
  rs::BusStats stats_a, stats_b;
  Rss rss_start, rss_mid, rss_end;
  const auto name = [&](const char* type, const std::string& a) { return std::string(type) + "@" + a; };
  load[0].name = name("sd1", sd1_addr[0]);
  load[1].name = name("sd1", sd1_addr[1]);
  load[2].name = name("so1", so1_addr);
  load[3].name = name("sbs1", sbs1_addr);

  try {
    // Known readings, so that a corrupted answer that got through would show.
    const double srf_m[2] = {1.5, 0.75}, ir_m = 0.2, beacon_deg = 123.45;
    const double rate = 400;  // ticks/s: 100 ticks per 4 Hz period, well inside width 2
    if (!control.empty()) {
      using advee::rs485sim::control_ok;
      for (int i = 0; i < 2; ++i) {
        control_ok(control, "set a:" + load[i].name + " srf all " + std::to_string(srf_m[i]));
        control_ok(control, "set a:" + load[i].name + " ir all " + std::to_string(ir_m));
      }
      control_ok(control, "set a:" + load[2].name + " rate " + std::to_string(rate) + " " + std::to_string(-rate));
      control_ok(control, "set b:" + load[3].name + " beacon 7 " + std::to_string(beacon_deg) + " 99");
    }
    rs::BusOptions opt;
    opt.config = rs::BusConfig{};
    opt.config->timeout = std::chrono::milliseconds(timeout_ms);
    opt.config->retries = retries;
    rs::Bus a(bus_a, opt), b(bus_b, opt);
    rs::Sd1 sd1[2] = {rs::Sd1(a, addr(sd1_addr[0])), rs::Sd1(a, addr(sd1_addr[1]))};
    rs::So1 so1(a, addr(so1_addr));
    rs::Sbs1 sbs1(b, addr(sbs1_addr));
    const std::uint8_t ids[] = {7};
    if (const auto ec = sbs1.set_beacon_ids(ids)) throw std::runtime_error("sbs1 set ids: " + ec.message());
    if (const auto ec = so1.reset_ticks()) throw std::runtime_error("so1 reset: " + ec.message());

    std::printf("rs485-load: %.0f s; bus a %s: %s %s %s at 4 Hz; bus b %s: %s at 1 Hz; timeout %u ms, retries %u, "
                "bound per call %.0f ms\n",
                seconds, bus_a.c_str(), load[0].name.c_str(), load[1].name.c_str(), load[2].name.c_str(),
                bus_b.c_str(), load[3].name.c_str(), timeout_ms, retries, lim.bound_ms);
    std::fflush(stdout);

    const auto end = Clock::now() + std::chrono::duration_cast<Clock::duration>(std::chrono::duration<double>(seconds));
    std::atomic<bool> warm{false};
    std::thread ta([&] {
      std::int64_t last_left = 0;
      auto next = Clock::now();
      for (unsigned cycle = 0; Clock::now() < end; ++cycle) {
        for (int i = 0; i < 2; ++i)
          poll_one(load[i], lim, [&] { return sd1[i].distances(); }, [&](const rs::Sd1Distances& d) {
            bool right = d.srf_m.size() == 8 && d.ir_m.size() == 2;
            for (const auto& m : d.srf_m) right = right && m && std::fabs(*m - srf_m[i]) < 0.006;
            for (const auto& m : d.ir_m) right = right && m && std::fabs(*m - ir_m) < 0.0021;
            return control.empty() || right;
          });
        poll_one(load[2], lim, [&] { return so1.counts(2); }, [&](const rs::So1Counts& c) {
          // The wheels turn forward at a constant rate: the count never goes back.
          // Left and right run at +rate and -rate: equal magnitudes, give or take
          // the rounding of the simulator's fractional ticks.
          const bool right = c.left >= last_left && std::abs(c.left + c.right) <= 1;
          last_left = c.left;
          return control.empty() || right;
        });
        if (cycle == 3) warm = true;
        next += 250ms;
        if (next < Clock::now()) {
          ++overruns_a;  // a cycle took longer than its period: do not catch up in a burst
          next = Clock::now();
        }
        std::this_thread::sleep_until(next);
      }
    });
    std::thread tb([&] {
      auto next = Clock::now();
      while (Clock::now() < end) {
        poll_one(load[3], lim, [&] { return sbs1.beacons(); }, [&](const std::vector<rs::BeaconBearing>& bs) {
          const bool right = bs.size() == 1 && bs[0].id == 7 && bs[0].quality == 99 &&
                             std::fabs(bs[0].bearing_rad - beacon_deg * std::numbers::pi / 180) < 1e-3;
          return control.empty() || right;
        });
        next += 1s;
        if (next < Clock::now()) {
          ++overruns_b;
          next = Clock::now();
        }
        std::this_thread::sleep_until(next);
      }
    });
    // RSS at start: after the first cycles, once every buffer and thread exists.
    while (!warm && Clock::now() < end) std::this_thread::sleep_for(50ms);
    rss_start = Rss::now();
    // Half-time sample: tells warm-up (flat after it) from a leak (linear).
    std::this_thread::sleep_until(Clock::now() + (end - Clock::now()) / 2);
    rss_mid = Rss::now();
    ta.join();
    tb.join();
    rss_end = Rss::now();
    stats_a = a.stats();
    stats_b = b.stats();
  } catch (const std::exception& e) {
    std::fprintf(stderr, "rs485-load: %s\n", e.what());
    return 2;
  }

  bool pass = true;
  std::uint64_t polls = 0, oks = 0, errors = 0;
  std::printf("%-12s %7s %7s %7s %7s %7s %9s  %s\n", "device", "polls", "ok", "errors", "unclear", "wrong", "max_ms",
              "errors by kind");
  for (const auto& d : load) {
    std::string kinds;
    std::uint64_t e = 0;
    for (const auto& [k, n] : d.errors) {
      kinds += k + "=" + std::to_string(n) + " ";
      e += n;
    }
    std::printf("%-12s %7llu %7llu %7llu %7llu %7llu %9.1f  %s\n", d.name.c_str(),
                static_cast<unsigned long long>(d.polls), static_cast<unsigned long long>(d.ok),
                static_cast<unsigned long long>(e), static_cast<unsigned long long>(d.unclear),
                static_cast<unsigned long long>(d.wrong_data), d.max_ms, kinds.empty() ? "-" : kinds.c_str());
    polls += d.polls;
    oks += d.ok;
    errors += e;
    if (d.unclear || d.wrong_data || d.polls == 0 || d.ok + e + d.unclear != d.polls) pass = false;
  }
  for (const auto& [bus, s] : {std::pair{"a", stats_a}, std::pair{"b", stats_b}})
    std::printf("bus %s: xfers %llu ok %llu failed %llu retries %llu timeouts %llu rx_crc_errors %llu unexpected %llu\n",
                bus, static_cast<unsigned long long>(s.xfers), static_cast<unsigned long long>(s.xfers_ok),
                static_cast<unsigned long long>(s.xfers_failed), static_cast<unsigned long long>(s.retries),
                static_cast<unsigned long long>(s.timeouts), static_cast<unsigned long long>(s.rx_crc_errors),
                static_cast<unsigned long long>(s.unexpected));
  std::printf("polls %llu ok %llu errors %llu; max call %.1f ms (bound %.0f ms), over bound %llu; "
              "late cycles a %llu b %llu\n",
              static_cast<unsigned long long>(polls), static_cast<unsigned long long>(oks),
              static_cast<unsigned long long>(errors), lim.max_ms.load(), lim.bound_ms,
              static_cast<unsigned long long>(lim.over_bound.load()), static_cast<unsigned long long>(overruns_a),
              static_cast<unsigned long long>(overruns_b));
  std::printf("rss start %ld kB half-time %ld kB end %ld kB (growth %ld kB, allowed %ld kB); "
              "anon %ld / %ld / %ld kB\n",
              rss_start.vm, rss_mid.vm, rss_end.vm, rss_end.vm - rss_start.vm, rss_slack_kb, rss_start.anon,
              rss_mid.anon, rss_end.anon);
  if (lim.over_bound || rss_start.vm < 0 || rss_end.vm - rss_start.vm > rss_slack_kb) pass = false;
  std::printf("result: %s\n", pass ? "PASS" : "FAIL");
  return pass ? 0 : 1;
}
