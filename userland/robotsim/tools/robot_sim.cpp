// SPDX-License-Identifier: GPL-2.0
// advee-robot-sim: the virtual robot. Loads a map and a robot description, drives
// the robot at a fixed rate, either along a scripted path, from a stream of
// commands, or with its two CANopen drives simulated on a CAN interface
// (--can), and publishes its sensor values to the device simulators
// (advee-rs485-sim control socket, MAX6615 debugfs), its true pose on LCM
// (--lcm), optionally printing pose, ranges and bearings once a second.
#include <CLI/CLI.hpp>
#include <fcntl.h>
#include <pthread.h>
#include <signal.h>
#include <sys/stat.h>
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <csignal>
#include <cstdio>
#include <memory>
#include <thread>
#include <vector>

#include "advee/cli.hpp"
#include "advee/robotsim/can_drives.hpp"
#include "advee/robotsim/robot.hpp"
#include "advee/robotsim/scripted_path.hpp"
#include "advee/robotsim/sinks.hpp"
#include "advee/robotsim/stream_drive.hpp"
#include "advee/robotsim/world.hpp"
#include "advee/rs485sim/control_client.hpp"
#ifdef ADVEE_ROBOTSIM_LCM
#include "advee/robotsim/pose_publisher.hpp"
#endif

using namespace advee::robotsim;

namespace {

// SIGINT/SIGTERM stop, SIGUSR1/SIGUSR2 inject drive faults. They stay
// blocked in every thread and are collected once per step: no handler can
// interrupt a control-socket poll half-way (EINTR) and the drives' thread
// never sees them.
class BlockedSignals {
 public:
  BlockedSignals() {
    sigemptyset(&set_);
    for (int s : {SIGINT, SIGTERM, SIGUSR1, SIGUSR2}) sigaddset(&set_, s);
    pthread_sigmask(SIG_BLOCK, &set_, nullptr);
  }
  // The next pending signal, 0 if none.
  int take() {
    const timespec now{};
    const int s = sigtimedwait(&set_, nullptr, &now);
    return s > 0 ? s : 0;
  }

 private:
  sigset_t set_;
};

// The drive input: "-" is stdin; a FIFO is opened read-write so that it
// never reads end-of-file while no writer has it open.
advee::UniqueFd open_drive_input(const std::string& path) {
  if (path == "-") return advee::UniqueFd(fcntl(0, F_DUPFD_CLOEXEC, 3));
  struct stat st {};
  const bool fifo = stat(path.c_str(), &st) == 0 && S_ISFIFO(st.st_mode);
  advee::UniqueFd fd(open(path.c_str(), (fifo ? O_RDWR : O_RDONLY) | O_NONBLOCK | O_CLOEXEC));
  if (!fd) throw std::system_error(errno, std::generic_category(), "drive input " + path);
  return fd;
}

void print_frame(const SensorFrame& f, const Pose& odo) {
  std::printf("t=%.1f pose x=%.3f y=%.3f heading=%.1f odo x=%.3f y=%.3f heading=%.1f v=%.2f steer=%.1f ticks=%lld,%lld\n",
              f.time_s, f.pose.position.x(), f.pose.position.y(), rad_to_deg(f.pose.heading), odo.position.x(),
              odo.position.y(), rad_to_deg(odo.heading), f.speed_mps, rad_to_deg(f.steering_rad),
              static_cast<long long>(f.ticks[0]), static_cast<long long>(f.ticks[1]));
  std::printf("  srf_m");
  for (const auto& r : f.srf_m) r ? std::printf(" %.2f", *r) : std::printf(" -");
  std::printf("\n  ir_m");
  for (const auto& r : f.ir_m) r ? std::printf(" %.3f", *r) : std::printf(" -");
  std::printf("\n  beacons");
  for (const auto& b : f.beacons) std::printf(" %u@%.2fdeg(q%u)", b.id, b.bearing_cdeg / 100.0, b.quality);
  std::printf("\n  pause=0x%02x temps_c", f.pause);
  for (double t : f.temperature_c) std::printf(" %.2f", t);
  std::printf("\n");
  std::fflush(stdout);
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{
      "advee-robot-sim - the virtual Advee robot.\n\n"
      "Drives an Ackermann robot through a 2D room (map file) and feeds the device\n"
      "simulators with what its sensors would measure: front-wheel encoder ticks (BR-SO1), 16 ultrasonic\n"
      "ranges and 4 IR ground distances (two BR-SD1), beacon bearings (BR-SBS1), bumper PAUSE sources\n"
      "(BR-SD1 GET_PAUSE_SRC) through the advee-rs485-sim control socket, and the MAX6615 temperatures through\n"
      "the kernel simulator's debugfs files. The world advances in fixed steps of 1/--rate seconds of\n"
      "simulated time, in real time unless --fast. The motion comes from a scripted path (--path), a\n"
      "command stream (--drive-input) or the robot's own CANopen drives (--can IF): a simulated EPOS\n"
      "(propulsion) and IclA (steering) that a CANopen master (driver_canbus, advee-canopenctl) commands.\n"
      "A bumper contact stops the robot and engages the PAUSE line (BR-PSC1 PAUSE event), which cuts\n"
      "the drive motor's power. docs/robotsim.md describes the model and the files.",
      "advee-robot-sim"};
  app.footer(
      "EXAMPLES:\n"
      "  advee-robot-sim --check                                   load the files, report errors, exit\n"
      "  advee-robot-sim --print --fast --duration 40              the scripted path without simulators\n"
      "  advee-robot-sim --rs485-control /run/rs485-sim.sock --max6615 /sys/kernel/debug/ts7800-sim/max6615\n"
      "  advee-robot-sim --can vcan0 --rs485-control /run/rs485-sim.sock --lcm --print\n\n"
      "EXIT STATUS:\n"
      "  0 done (--duration reached, or SIGINT/SIGTERM)\n"
      "  1 an unusable map, robot or path file (the message names file, line and field), a simulator\n"
      "    refused a value or could not be reached, CAN or LCM failed, or a bad --drive-input line\n"
      "  2 bad command line (an unknown option, a bad value, options that exclude each other)\n\n"
      "DRIVE INPUT (--drive-input): text lines 'SPEED_MPS STEERING_DEG' (steering counter-clockwise,\n"
      "'#' comments); the last line holds, the robot stands still until the first.\n\n"
      "DRIVES (--can): EPOS node 1 (0x60FF/0x606C in motor rpm), IclA node 2 (0x607A/0x6064 in\n"
      "1/10000 rad of steering, 0 = straight ahead after homing); robot.yaml's drives: section sets\n"
      "nodes, gear, wheel radius, units, home switch and start angle. They behave like\n"
      "advee-canopen-sim-drive's (NMT, SDO, PDOs, heartbeat, CiA 402). Signals: SIGUSR1 = EMCY 0x4210 + fault\n"
      "on the EPOS, SIGUSR2 = heartbeat silence of both on/off.");
  const std::string etc = ADVEE_ROBOTSIM_SYSCONFDIR "/";
  std::string map_file = etc + "room.yaml", robot_file = etc + "robot.yaml", path_file = etc + "square-path.yaml";
  double rate = 100, publish_rate = 10, duration = 0;
  unsigned seed = 1;
  bool print = false, fast = false, check = false;
  std::string rs485_control, max6615_dir, drive_input, can_if, lcm_url;
  Rs485Devices devices;
  app.add_option("-m,--map", map_file, "map file: walls, obstacles, beacons")->capture_default_str();
  app.add_option("-r,--robot", robot_file, "robot description: chassis, start pose, sensors, thermal model")
      ->capture_default_str();
  app.add_option("-p,--path", path_file, "scripted drive: list of {speed_mps, steering_deg, duration_s}")
      ->capture_default_str();
  auto* input_opt = app.add_option("--drive-input", drive_input,
                                   "read the drive commands from this file, FIFO or '-' (stdin) instead of --path");
  app.add_option("--can", can_if, "run the simulated EPOS and IclA on this CAN interface (e.g. vcan0); the robot "
                                  "moves as they do (real time only)")
      ->excludes(input_opt);
  auto* lcm_opt = app.add_option("--lcm", lcm_url, "publish the true pose on SIM_DATA_POSE at 10 Hz; optional LCM "
                                                   "URL (default: LCM_DEFAULT_URL, else /etc/advee/lcm.conf, else LCM's own default)")
                      ->expected(0, 1);
  app.add_option("--rate", rate, "simulation steps per second")->check(CLI::Range(1.0, 10000.0))->capture_default_str();
  app.add_option("--publish-rate", publish_rate, "sensor frames per second sent to the simulators")
      ->check(CLI::Range(0.1, 1000.0))->capture_default_str();
  app.add_option("-d,--duration", duration, "simulated seconds to run; 0 = until SIGINT/SIGTERM (the robot stands "
                                            "still once the path ends)")
      ->check(CLI::NonNegativeNumber)->capture_default_str();
  app.add_option("--seed", seed, "random seed of the sensor noise (same seed, same readings)")->capture_default_str();
  app.add_option("--rs485-control", rs485_control, "advee-rs485-sim control socket to publish to (none: not published)");
  app.add_option("--sd1-front", devices.sd1_front, "front BR-SD1 as advee-rs485-sim names it ([BUS:]TYPE@ADDRESS)")
      ->capture_default_str();
  app.add_option("--sd1-rear", devices.sd1_rear, "rear BR-SD1")->capture_default_str();
  app.add_option("--so1", devices.so1, "BR-SO1 odometry board")->capture_default_str();
  app.add_option("--sbs1", devices.sbs1, "BR-SBS1 beacon scanner")->capture_default_str();
  app.add_option("--psc1", devices.psc1, "BR-PSC1 that reports the PAUSE line ('' = none)")->capture_default_str();
  app.add_option("--max6615", max6615_dir,
                 "MAX6615 model's debugfs directory (e.g. /sys/kernel/debug/ts7800-sim/max6615; none: not written)");
  app.add_flag("--print", print, "print pose, odometry, ranges, bearings, PAUSE and temperatures once per "
                                 "simulated second");
  app.add_flag("--fast", fast, "do not wait for real time between steps");
  app.add_flag("--check", check, "load the map, robot and path files, report errors, exit");
  ADVEE_CLI_PARSE(app, argc, argv);
  if (!can_if.empty() && fast)
    return advee::cli::usage_error(app, "--can runs in real time (the drives follow the clock): drop --fast");
#ifndef ADVEE_ROBOTSIM_LCM
  if (lcm_opt->count()) return advee::cli::usage_error(app, "built without LCM: --lcm is not available");
#endif

  World world;
  RobotDescription desc;
  ScriptedPath path;
  try {
    world = load_world(map_file);
    desc = load_robot(robot_file);
    if (drive_input.empty() && can_if.empty()) path = load_path(path_file);
  } catch (const ConfigError& e) {
    std::fprintf(stderr, "advee-robot-sim: %s\n", e.what());
    return 1;
  }
  Robot robot(desc, world, seed);
  if (robot.bumper_contact(robot.pose())) {
    std::fprintf(stderr, "advee-robot-sim: %s: the start pose touches a wall or obstacle of %s\n", robot_file.c_str(),
                 map_file.c_str());
    return 1;
  }
  if (check) {
    std::printf("ok: %zu wall/box segments, %zu circles, %zu beacons; %zu SRF, %zu IR; path %.1f s\n",
                world.segments().size(), world.circles().size(), world.beacons().size(), desc.srf.sensors.size(),
                desc.ir.sensors.size(), path.duration());
    return 0;
  }

  std::vector<std::unique_ptr<SensorSink>> sinks;
  if (!rs485_control.empty())
    sinks.push_back(std::make_unique<Rs485SimSink>(devices, desc, [&](const std::string& cmd) {
      advee::rs485sim::control_ok(rs485_control, cmd);
    }));
  if (!max6615_dir.empty()) sinks.push_back(std::make_unique<Max6615DebugfsSink>(max6615_dir));
  BlockedSignals signals;  // before the drives' thread starts: it inherits the mask
  std::unique_ptr<DriveSource> drive;
  CanDrives* can = nullptr;
  try {
    if (!can_if.empty()) {
      auto d = std::make_unique<CanDrives>(can_if, desc.drives);
      can = d.get();
      drive = std::move(d);
    } else if (drive_input.empty()) {
      drive = std::make_unique<ScriptedDrive>(path);
    } else {
      drive = std::make_unique<StreamDrive>(open_drive_input(drive_input));
    }
  } catch (const std::system_error& e) {
    std::fprintf(stderr, "advee-robot-sim: %s\n", e.what());
    return 1;
  }
#ifdef ADVEE_ROBOTSIM_LCM
  std::unique_ptr<PosePublisher> pose_pub;
  if (lcm_opt->count()) {
    try {
      pose_pub = std::make_unique<PosePublisher>(lcm_url);
    } catch (const std::exception& e) {
      std::fprintf(stderr, "advee-robot-sim: %s\n", e.what());
      return 1;
    }
  }
#endif
  if (can) {
    std::printf("drives on %s: EPOS node %u, IclA node %u\n", can_if.c_str(), desc.drives.propulsion_node,
                desc.drives.steering_node);
    std::fflush(stdout);
  }
  TickOdometry odo(desc.chassis, robot.pose());


  const double dt = 1.0 / rate;
  const long steps_per_publish = std::max(1L, std::lround(rate / publish_rate));
  const long steps_per_print = std::max(1L, std::lround(rate));
  [[maybe_unused]] const long steps_per_pose = std::max(1L, std::lround(rate / 10));  // SIM_DATA_POSE at 10 Hz
  const long total = duration > 0 ? std::lround(duration * rate) : -1;
  auto next = std::chrono::steady_clock::now();
  try {
    bool stop = false;
    for (long i = 1; !stop && (total < 0 || i <= total); ++i) {
      for (int sig; (sig = signals.take()) != 0;) {
        if (sig == SIGUSR1 && can) {
          std::printf("EPOS: inject EMCY 0x4210\n");
          can->inject_fault(desc.drives.propulsion_node, 0x4210);
        } else if (sig == SIGUSR2 && can) {
          std::printf("drives: heartbeat %s\n", can->toggle_heartbeat_silence() ? "silent" : "on");
        } else if (sig == SIGINT || sig == SIGTERM) {
          stop = true;
        }
      }
      if (stop) break;
      const DriveCommand cmd = drive->command(robot.time());
      robot.step(cmd.speed_mps, cmd.steering_rad, dt);
#ifdef ADVEE_ROBOTSIM_LCM
      if (pose_pub && i % steps_per_pose == 0) pose_pub->publish(robot);
#endif
      const bool publish = i % steps_per_publish == 0, show = print && i % steps_per_print == 0;
      if (publish || show) {
        const SensorFrame f = robot.sense();
        if (publish) {
          for (auto& s : sinks) s->publish(f);
          odo.update(f.ticks[0], f.ticks[1]);
        }
        if (show) {
          print_frame(f, odo.pose());
          if (can) {
            const DriveStatus d = can->status();
            std::printf("  drives epos=%s %.1frpm icla=%s pos=%.0f\n",
                        std::string(advee::canopen::cia402::to_string(d.epos_state)).c_str(), d.epos_rpm,
                        std::string(advee::canopen::cia402::to_string(d.icla_state)).c_str(), d.icla_position);
            std::fflush(stdout);
          }
        }
      }
      if (!fast) {
        next += std::chrono::duration_cast<std::chrono::steady_clock::duration>(std::chrono::duration<double>(dt));
        std::this_thread::sleep_until(next);
      }
    }
  } catch (const std::exception& e) {
    std::fprintf(stderr, "advee-robot-sim: %s\n", e.what());
    return 1;
  }
  return 0;
}
