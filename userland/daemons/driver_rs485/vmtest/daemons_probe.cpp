// SPDX-License-Identifier: GPL-2.0
// advee-daemons-probe: the test end of the driver daemons' channels
// (tests/vm/daemons/). The LCM URL is LCM_DEFAULT_URL.
//   listen SECONDS CHANNEL...   one decoded line per message until SECONDS pass:
//                               "CHANNEL t=RECEIVE_S key=value ..." (t: CLOCK_MONOTONIC)
//   active-beacons ID...        publish LL_DATA_ACTIVE_BEACONS
//   power output N on|off | power poweroff | power reboot     publish LL_CMD_POWER
//   motion SPEED_MPS STEER_RAD HZ SECONDS                     publish LL_CMD_MOTION at HZ
//                               (then prints "last_utime=US", CLOCK_REALTIME of the last one)
//   homing                      publish LL_CMD_HOMING (steering)
//   stop on|off                 publish LL_EVENT_STOP (stop=1|0, source DIO)
// LL_DATA_DRIVES and CM_DATA_ERROR are decoded too (spaces in texts become '_').
#include <poll.h>

#include <chrono>
#include <cstdio>
#include <cstring>
#include <iostream>
#include <lcm/lcm-cpp.hpp>
#include <string>
#include <thread>
#include <vector>

#include "advee/msgs/describe.hpp"
#include "common/error_t.hpp"
#include "lowlevel/cmd_homing_t.hpp"
#include "lowlevel/cmd_motion_t.hpp"
#include "lowlevel/cmd_power_t.hpp"
#include "lowlevel/data_active_beacons_t.hpp"
#include "lowlevel/data_beacons_t.hpp"
#include "lowlevel/data_drives_t.hpp"
#include "lowlevel/data_odo_t.hpp"
#include "lowlevel/data_power_t.hpp"
#include "lowlevel/data_srfs_t.hpp"
#include "lowlevel/event_stop_t.hpp"

namespace {

double mono_s() {
  return std::chrono::duration<double>(std::chrono::steady_clock::now().time_since_epoch()).count();
}

std::int64_t utime() {
  return std::chrono::duration_cast<std::chrono::microseconds>(
             std::chrono::system_clock::now().time_since_epoch())
      .count();
}

struct Printer {
  void on(const lcm::ReceiveBuffer* rb, const std::string& ch) { std::cout << advee::msgs::describe(*rb, ch) << std::endl; }
};

int usage() {
  std::cerr << "usage: advee-daemons-probe listen SECONDS CHANNEL... | active-beacons ID... |\n"
               "       power output N on|off | power poweroff|reboot | motion SPEED STEER HZ SECONDS | homing |\n"
               "       stop on|off\n";
  return 2;
}

}  // namespace

int main(int argc, char** argv) {
  if (argc < 2) return usage();
  lcm::LCM lcm;
  if (!lcm.good()) {
    std::cerr << "advee-daemons-probe: LCM did not start (multicast route?)\n";
    return 3;
  }
  const std::string cmd = argv[1];
  std::vector<std::string> a(argv + 2, argv + argc);
  try {
    if (cmd == "listen" && a.size() >= 2) {
      Printer p;
      for (std::size_t i = 1; i < a.size(); ++i) lcm.subscribe(a[i], &Printer::on, &p);
      const double end = mono_s() + std::stod(a[0]);
      while (mono_s() < end) {
        pollfd pfd{lcm.getFileno(), POLLIN, 0};
        const int left_ms = static_cast<int>((end - mono_s()) * 1000) + 1;
        if (::poll(&pfd, 1, left_ms) > 0) lcm.handle();
      }
      return 0;
    }
    if (cmd == "active-beacons") {
      lowlevel::data_active_beacons_t m{};
      m.utime = utime();
      m.module = "daemons-probe";
      for (const auto& s : a) m.id.push_back(static_cast<std::int16_t>(std::stoi(s)));
      m.count = static_cast<std::int16_t>(m.id.size());
      return lcm.publish("LL_DATA_ACTIVE_BEACONS", &m) == 0 ? 0 : 3;
    }
    if (cmd == "power" && !a.empty()) {
      lowlevel::cmd_power_t m{};
      m.utime = utime();
      m.module = "daemons-probe";
      if (a[0] == "output" && a.size() == 3) {
        m.action = lowlevel::cmd_power_t::ACTION_SET_OUTPUT;
        m.output = static_cast<std::int8_t>(std::stoi(a[1]));
        m.on = a[2] == "on";
      } else if (a[0] == "poweroff" && a.size() == 1) {
        m.action = lowlevel::cmd_power_t::ACTION_POWEROFF;
      } else if (a[0] == "reboot" && a.size() == 1) {
        m.action = lowlevel::cmd_power_t::ACTION_REBOOT;
      } else {
        return usage();
      }
      return lcm.publish("LL_CMD_POWER", &m) == 0 ? 0 : 3;
    }
    if (cmd == "motion" && a.size() == 4) {
      lowlevel::cmd_motion_t m{};
      m.module = "daemons-probe";
      m.speed_mps = std::stod(a[0]);
      m.steering_rad = std::stod(a[1]);
      const double hz = std::stod(a[2]);
      const double end = mono_s() + std::stod(a[3]);
      std::int64_t last = 0;
      while (mono_s() < end) {
        m.utime = utime();
        if (lcm.publish("LL_CMD_MOTION", &m) != 0) return 3;
        last = m.utime;
        std::this_thread::sleep_for(std::chrono::duration<double>(1.0 / hz));
      }
      std::cout << "last_utime=" << last << std::endl;
      return 0;
    }
    if (cmd == "homing" && a.empty()) {
      lowlevel::cmd_homing_t m{};
      m.utime = utime();
      m.module = "daemons-probe";
      m.axis = lowlevel::cmd_homing_t::AXIS_STEERING;
      return lcm.publish("LL_CMD_HOMING", &m) == 0 ? 0 : 3;
    }
    if (cmd == "stop" && a.size() == 1 && (a[0] == "on" || a[0] == "off")) {
      lowlevel::event_stop_t m{};
      m.utime = utime();
      m.module = "daemons-probe";
      m.stop = a[0] == "on";
      m.source = lowlevel::event_stop_t::SOURCE_DIO;
      return lcm.publish("LL_EVENT_STOP", &m) == 0 ? 0 : 3;
    }
  } catch (const std::exception& e) {
    std::cerr << "advee-daemons-probe: " << e.what() << "\n";
    return 2;
  }
  return usage();
}
