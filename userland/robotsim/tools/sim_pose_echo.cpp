// SPDX-License-Identifier: GPL-2.0
// advee-robot-sim-pose: prints advee-robot-sim's ground truth (SIM_DATA_POSE) one line
// per message, for tests and for a look at the virtual robot by hand.
#include <CLI/CLI.hpp>
#include <sys/select.h>

#include <chrono>
#include <cmath>
#include <cstdio>
#include <lcm/lcm-cpp.hpp>

#include "advee/cli.hpp"
#include "advee/msgs/bus.hpp"
#include "advee/robotsim/pose_publisher.hpp"
#include "sim/data_pose_t.hpp"

namespace {

struct Printer {
  long count = 0;
};

void on_pose(const lcm::ReceiveBuffer*, const std::string&, const sim::data_pose_t* m, Printer* p) {
  std::printf("SIM_DATA_POSE t=%.2f x=%.4f y=%.4f heading_deg=%.3f speed=%.4f steering_deg=%.3f pause=%d "
              "engaged=%d ticks=%lld,%lld\n",
              m->sim_time_s, m->x_m, m->y_m, m->heading_rad * 180 / M_PI, m->speed_mps,
              m->steering_rad * 180 / M_PI, m->pause_sources, m->pause_engaged ? 1 : 0,
              static_cast<long long>(m->ticks_left), static_cast<long long>(m->ticks_right));
  std::fflush(stdout);
  ++p->count;
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{"advee-robot-sim-pose - print advee-robot-sim's true pose (LCM channel SIM_DATA_POSE), one line per message:\n"
               "simulated time, x, y (m), heading (deg), speed (m/s), steering (deg), PAUSE sources and line,\n"
               "encoder ticks.",
               "advee-robot-sim-pose"};
  std::string url;
  double seconds = 0;
  long count = 0;
  app.add_option("--url", url, "LCM URL (default: LCM_DEFAULT_URL, else /etc/advee/lcm.conf, else LCM's default group)");
  app.add_option("-t,--timeout", seconds, "stop after this many seconds (0 = never)")->check(CLI::NonNegativeNumber);
  app.add_option("-n,--count", count, "stop after this many messages (0 = no limit)")->check(CLI::NonNegativeNumber);
  app.footer("EXIT STATUS: 0 at least one message, 1 none (or LCM failed), 2 bad option");
  ADVEE_CLI_PARSE(app, argc, argv);
  std::unique_ptr<lcm::LCM> bus;
  try {
    bus = advee::msgs::open_bus(advee::msgs::bus_url(url, "--url"));
  } catch (const advee::msgs::BusUnavailable& e) {
    std::fprintf(stderr, "advee-robot-sim-pose: %s\n", e.what());
    return 1;
  }
  lcm::LCM& lcm = *bus;
  Printer p;
  lcm.subscribeFunction(advee::robotsim::kSimDataPoseChannel, &on_pose, &p);
  const auto end = std::chrono::steady_clock::now() + std::chrono::duration<double>(seconds);
  while ((count == 0 || p.count < count) && (seconds == 0 || std::chrono::steady_clock::now() < end)) {
    const int ms = seconds == 0 ? 1000
                                : static_cast<int>(std::max<long>(
                                      0, std::chrono::duration_cast<std::chrono::milliseconds>(
                                             end - std::chrono::steady_clock::now()).count()));
    if (lcm.handleTimeout(std::max(1, ms)) < 0) return 1;
  }
  return p.count > 0 ? 0 : 1;
}
