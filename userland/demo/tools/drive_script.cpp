// SPDX-License-Identifier: GPL-2.0
// advee-drive-script: the planner stand-in of the demo. Plays a scripted
// path (speed/steering/duration segments, robotsim's path file format) onto
// LL_CMD_MOTION at a fixed rate, as the middle level would, so that the robot
// moves through driver_canbus -> drives -> advee-robot-sim. It also tells the
// beacon scanner which beacons to look for (LL_DATA_ACTIVE_BEACONS) and can
// ask for the steering homing first (LL_CMD_HOMING).
#include <lcm/lcm-cpp.hpp>
#include <poll.h>

#include <CLI/CLI.hpp>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <iostream>
#include <string>
#include <vector>

#include "advee/cli.hpp"
#include "advee/demo/motion_script.hpp"
#include "advee/module/periodic.hpp"
#include "advee/signal_fd.hpp"
#include "advee/module/time.hpp"
#include "advee/msgs/bus.hpp"
#include "advee/msgs/channels.hpp"
#include "advee/robotsim/world.hpp"
#include "lowlevel/cmd_homing_t.hpp"
#include "lowlevel/cmd_motion_t.hpp"
#include "lowlevel/data_active_beacons_t.hpp"

namespace {

using namespace std::chrono_literals;
using Clock = std::chrono::steady_clock;
constexpr const char* kSender = "drive_script";

struct Options {
  std::string path_file;
  double rate_hz = 10;
  double hold_s = 2;
  double delay_s = 0;
  bool stay = false;
  bool home = false;
  double home_wait_s = 3;
  std::vector<int> beacons;
  double beacons_every_s = 5;
  bool quiet = false;
};

double seconds_since(Clock::time_point t0) { return std::chrono::duration<double>(Clock::now() - t0).count(); }

class Publisher {
 public:
  explicit Publisher(lcm::LCM& lcm) : lcm_(lcm) {}

  void motion(double speed_mps, double steering_rad) {
    lowlevel::cmd_motion_t m;
    m.utime = advee::module::utime_now();
    m.module = kSender;
    m.speed_mps = speed_mps;
    m.steering_rad = steering_rad;
    publish(advee::msgs::kCmdMotion.name, m);
  }

  void homing() {
    lowlevel::cmd_homing_t m;
    m.utime = advee::module::utime_now();
    m.module = kSender;
    m.axis = lowlevel::cmd_homing_t::AXIS_STEERING;
    publish(advee::msgs::kCmdHoming.name, m);
  }

  void active_beacons(const std::vector<int>& ids) {
    lowlevel::data_active_beacons_t m;
    m.utime = advee::module::utime_now();
    m.module = kSender;
    m.count = static_cast<std::int16_t>(ids.size());
    for (int id : ids) m.id.push_back(static_cast<std::int16_t>(id));
    publish(advee::msgs::kDataActiveBeacons.name, m);
  }

 private:
  template <typename Msg>
  void publish(std::string_view channel, const Msg& m) {
    if (lcm_.publish(std::string(channel), &m) != 0)
      throw std::runtime_error("cannot publish on " + std::string(channel));
  }
  lcm::LCM& lcm_;
};

// Waits for the next tick of `timer`; false when SIGINT/SIGTERM arrived.
bool next_tick(advee::module::PeriodicTimer& timer, advee::SignalFd& signals) {
  for (;;) {
    pollfd fds[2] = {{timer.fd(), POLLIN, 0}, {signals.fd(), POLLIN, 0}};
    if (::poll(fds, 2, -1) < 0) {
      if (errno == EINTR) continue;
      throw std::system_error(errno, std::generic_category(), "poll");
    }
    if (fds[1].revents & POLLIN) return false;
    if ((fds[0].revents & POLLIN) && timer.consume() > 0) return true;
  }
}

int run(const Options& o) {
  const advee::demo::MotionScript script(advee::robotsim::load_path(o.path_file));
  // Signals first: LCM's threads inherit the blocked mask.
  advee::SignalFd signals({SIGINT, SIGTERM});
  std::unique_ptr<lcm::LCM> bus;
  try {
    bus = advee::msgs::open_bus(advee::msgs::bus_url(""));
  } catch (const advee::msgs::BusUnavailable& e) {
    std::cerr << "advee-drive-script: " << e.what() << "\n";
    return 1;
  }
  lcm::LCM& lcm = *bus;
  Publisher pub(lcm);
  const auto period = std::chrono::duration_cast<std::chrono::nanoseconds>(std::chrono::duration<double>(1 / o.rate_hz));
  advee::module::PeriodicTimer timer(period);
  auto say = [&](const std::string& s) {
    if (!o.quiet) std::cout << "advee-drive-script: " << s << std::endl;
  };

  auto beacons_sent = Clock::time_point{};
  auto maybe_beacons = [&] {
    if (o.beacons.empty() || (beacons_sent != Clock::time_point{} && seconds_since(beacons_sent) < o.beacons_every_s))
      return;
    pub.active_beacons(o.beacons);
    beacons_sent = Clock::now();
  };

  // Standstill while waiting: the drives see commands (no timeout stop).
  auto wait_standing = [&](double secs, const std::string& why) {
    if (secs <= 0) return true;
    say(why);
    const auto t0 = Clock::now();
    while (seconds_since(t0) < secs) {
      if (!next_tick(timer, signals)) return false;
      maybe_beacons();
      pub.motion(0, 0);
    }
    return true;
  };

  auto stop_and_exit = [&] {
    pub.motion(0, 0);
    say("stopped by signal");
    return 0;
  };

  maybe_beacons();
  if (!wait_standing(o.delay_s, "waiting " + std::to_string(o.delay_s) + " s before the path")) return stop_and_exit();
  if (o.home) {
    pub.homing();
    if (!wait_standing(o.home_wait_s, "steering homing requested")) return stop_and_exit();
  }

  char line[160];
  std::snprintf(line, sizeof line, "path %s: %zu segments, %.2f s", o.path_file.c_str(),
                script.path().segments().size(), script.duration());
  say(line);
  const auto t0 = Clock::now();
  std::size_t shown = SIZE_MAX;
  for (;;) {
    const auto cmd = script.at(seconds_since(t0));
    if (!cmd) break;
    if (cmd->segment != shown) {
      shown = cmd->segment;
      std::snprintf(line, sizeof line, "segment %zu/%zu: %.2f m/s, steering %.1f deg", shown + 1,
                    script.path().segments().size(), cmd->speed_mps, cmd->steering_rad * 180 / M_PI);
      say(line);
    }
    pub.motion(cmd->speed_mps, cmd->steering_rad);
    maybe_beacons();
    if (!next_tick(timer, signals)) return stop_and_exit();
  }
  pub.motion(0, 0);
  say("path done");
  if (o.stay) {
    while (next_tick(timer, signals)) {
      maybe_beacons();
      pub.motion(0, 0);
    }
    return stop_and_exit();
  }
  if (!wait_standing(o.hold_s, "holding still")) return stop_and_exit();
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  Options o;
  CLI::App app{
      "advee-drive-script: the planner stand-in of the demo. Plays a scripted path onto LL_CMD_MOTION "
      "(lowlevel.cmd_motion_t) at a fixed rate, as the middle level would: driver_canbus turns the commands "
      "into EPOS velocity and IclA steering, and the virtual robot (advee-robot-sim) moves as its simulated drives "
      "turn. After the path it sends standstill commands for --hold seconds (or until SIGINT/SIGTERM with "
      "--stay); SIGINT/SIGTERM send one standstill command and end it at once. The LCM URL comes from "
      "LCM_DEFAULT_URL, else /etc/advee/lcm.conf (docs/modules.md).\n\n"
      "Path file (robotsim's format, docs/robotsim.md):\n"
      "  path:\n"
      "    - {speed_mps: 0.5, steering_deg: 0, duration_s: 8}\n"
      "    - {speed_mps: 0.4, steering_deg: 20, duration_s: 6.68}\n\n"
      "Exit status: 0 path played (or stopped by a signal), 1 bad path file, LCM or publishing error, 2 bad\n"
      "command line.",
      "advee-drive-script"};
  app.get_formatter()->column_width(34);
  app.add_option("-p,--path", o.path_file, "scripted path file (YAML: path: [{speed_mps, steering_deg, duration_s}])")
      ->required()
      ->check(CLI::ExistingFile);
  app.add_option("-r,--rate", o.rate_hz, "LL_CMD_MOTION messages per second (driver_canbus stops after 1 s without one)")
      ->check(CLI::Range(1.5, 100.0))
      ->capture_default_str();
  app.add_option("--delay", o.delay_s, "seconds of standstill commands before the path")
      ->check(CLI::Range(0.0, 3600.0))
      ->capture_default_str();
  app.add_option("--hold", o.hold_s, "seconds of standstill commands after the path")
      ->check(CLI::Range(0.0, 3600.0))
      ->capture_default_str();
  app.add_flag("--stay", o.stay, "after the path keep sending standstill commands until SIGINT/SIGTERM");
  app.add_flag("--home", o.home, "send LL_CMD_HOMING (steering) first and wait --home-wait seconds");
  app.add_option("--home-wait", o.home_wait_s, "seconds to wait after the homing command")
      ->check(CLI::Range(0.0, 600.0))
      ->capture_default_str();
  app.add_option("-b,--beacons", o.beacons,
                 "beacon ids for LL_DATA_ACTIVE_BEACONS, sent at the start and every --beacons-every seconds")
      ->delimiter(',')
      ->check(CLI::Range(0, 255));
  app.add_option("--beacons-every", o.beacons_every_s, "seconds between LL_DATA_ACTIVE_BEACONS messages")
      ->check(CLI::Range(0.5, 3600.0))
      ->capture_default_str();
  app.add_flag("-q,--quiet", o.quiet, "do not print the segments as they start");
  ADVEE_CLI_PARSE(app, argc, argv);
  try {
    return run(o);
  } catch (const std::exception& e) {  // also a bad path file (robotsim::ConfigError)
    std::cerr << "advee-drive-script: " << e.what() << "\n";
    return 1;
  }
}
