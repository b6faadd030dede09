// SPDX-License-Identifier: GPL-2.0
// robot-sim: the virtual robot. Loads a map and a robot description, drives
// the robot along a scripted path at a fixed rate and publishes its sensor
// values to the device simulators (rs485-sim control socket, MAX6615
// debugfs), optionally printing pose, ranges and bearings once a second.
#include <CLI/CLI.hpp>
#include <fcntl.h>
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

#include "advee/robotsim/robot.hpp"
#include "advee/robotsim/scripted_path.hpp"
#include "advee/robotsim/sinks.hpp"
#include "advee/robotsim/stream_drive.hpp"
#include "advee/robotsim/world.hpp"
#include "advee/rs485sim/control_client.hpp"

using namespace advee::robotsim;

namespace {

volatile std::sig_atomic_t g_stop = 0;
void on_signal(int) { g_stop = 1; }

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
      "robot-sim - the virtual Advee robot.\n\n"
      "Drives an Ackermann robot through a 2D room (map file) along a scripted path and feeds the device\n"
      "simulators with what its sensors would measure: front-wheel encoder ticks (BR-SO1), 16 ultrasonic\n"
      "ranges and 4 IR ground distances (two BR-SD1), beacon bearings (BR-SBS1), bumper PAUSE sources\n"
      "(BR-SD1 GET_PAUSE_SRC) through the rs485-sim control socket, and the MAX6615 temperatures through\n"
      "the kernel simulator's debugfs files. The world advances in fixed steps of 1/--rate seconds of\n"
      "simulated time, in real time unless --fast. docs/robotsim.md describes the model and the files.",
      "robot-sim"};
  app.footer(
      "EXAMPLES:\n"
      "  robot-sim --check                                   load the files, report errors, exit\n"
      "  robot-sim --print --fast --duration 40              the scripted path without simulators\n"
      "  robot-sim --rs485-control /run/rs485-sim.sock --max6615 /sys/kernel/debug/ts7800-sim/max6615\n\n"
      "EXIT STATUS:\n"
      "  0 done (--duration reached, or SIGINT/SIGTERM)\n"
      "  1 a simulator refused a value or could not be reached, or a bad --drive-input line\n"
      "  2 bad option or unusable map, robot or path file (the message names file, line and field)\n\n"
          "DRIVE INPUT (--drive-input): text lines 'SPEED_MPS STEERING_DEG' (steering counter-clockwise,\n"
      "'#' comments); the last line holds, the robot stands still until the first. Without it the\n"
      "scripted --path drives: the simulated EPOS/IclA (canopen-sim-drive) offer no hook to read\n"
      "their speed and steering yet.");
  const std::string etc = ADVEE_ROBOTSIM_SYSCONFDIR "/";
  std::string map_file = etc + "room.yaml", robot_file = etc + "robot.yaml", path_file = etc + "square-path.yaml";
  double rate = 100, publish_rate = 10, duration = 0;
  unsigned seed = 1;
  bool print = false, fast = false, check = false;
  std::string rs485_control, max6615_dir, drive_input;
  Rs485Devices devices;
  app.add_option("-m,--map", map_file, "map file: walls, obstacles, beacons")->capture_default_str();
  app.add_option("-r,--robot", robot_file, "robot description: chassis, start pose, sensors, thermal model")
      ->capture_default_str();
  app.add_option("-p,--path", path_file, "scripted drive: list of {speed_mps, steering_deg, duration_s}")
      ->capture_default_str();
  app.add_option("--drive-input", drive_input,
                 "read the drive commands from this file, FIFO or '-' (stdin) instead of --path");
  app.add_option("--rate", rate, "simulation steps per second")->check(CLI::Range(1.0, 10000.0))->capture_default_str();
  app.add_option("--publish-rate", publish_rate, "sensor frames per second sent to the simulators")
      ->check(CLI::Range(0.1, 1000.0))->capture_default_str();
  app.add_option("-d,--duration", duration, "simulated seconds to run; 0 = until SIGINT/SIGTERM (the robot stands "
                                            "still once the path ends)")
      ->check(CLI::NonNegativeNumber)->capture_default_str();
  app.add_option("--seed", seed, "random seed of the sensor noise (same seed, same readings)")->capture_default_str();
  app.add_option("--rs485-control", rs485_control, "rs485-sim control socket to publish to (none: not published)");
  app.add_option("--sd1-front", devices.sd1_front, "front BR-SD1 as rs485-sim names it ([BUS:]TYPE@ADDRESS)")
      ->capture_default_str();
  app.add_option("--sd1-rear", devices.sd1_rear, "rear BR-SD1")->capture_default_str();
  app.add_option("--so1", devices.so1, "BR-SO1 odometry board")->capture_default_str();
  app.add_option("--sbs1", devices.sbs1, "BR-SBS1 beacon scanner")->capture_default_str();
  app.add_option("--max6615", max6615_dir,
                 "MAX6615 model's debugfs directory (e.g. /sys/kernel/debug/ts7800-sim/max6615; none: not written)");
  app.add_flag("--print", print, "print pose, odometry, ranges, bearings, PAUSE and temperatures once per "
                                 "simulated second");
  app.add_flag("--fast", fast, "do not wait for real time between steps");
  app.add_flag("--check", check, "load the map, robot and path files, report errors, exit");
  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    return app.exit(e) == 0 ? 0 : 2;
  }

  World world;
  RobotDescription desc;
  ScriptedPath path;
  try {
    world = load_world(map_file);
    desc = load_robot(robot_file);
    if (drive_input.empty()) path = load_path(path_file);
  } catch (const ConfigError& e) {
    std::fprintf(stderr, "robot-sim: %s\n", e.what());
    return 2;
  }
  Robot robot(desc, world, seed);
  if (robot.bumper_contact(robot.pose())) {
    std::fprintf(stderr, "robot-sim: %s: the start pose touches a wall or obstacle of %s\n", robot_file.c_str(),
                 map_file.c_str());
    return 2;
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
  std::unique_ptr<DriveSource> drive;
  try {
    if (drive_input.empty())
      drive = std::make_unique<ScriptedDrive>(path);
    else
      drive = std::make_unique<StreamDrive>(open_drive_input(drive_input));
  } catch (const std::system_error& e) {
    std::fprintf(stderr, "robot-sim: %s\n", e.what());
    return 2;
  }
  TickOdometry odo(desc.chassis, robot.pose());

  struct sigaction sa {};
  sa.sa_handler = on_signal;
  sigaction(SIGINT, &sa, nullptr);
  sigaction(SIGTERM, &sa, nullptr);

  const double dt = 1.0 / rate;
  const long steps_per_publish = std::max(1L, std::lround(rate / publish_rate));
  const long steps_per_print = std::max(1L, std::lround(rate));
  const long total = duration > 0 ? std::lround(duration * rate) : -1;
  auto next = std::chrono::steady_clock::now();
  try {
    for (long i = 1; !g_stop && (total < 0 || i <= total); ++i) {
      const DriveCommand cmd = drive->command(robot.time());
      robot.step(cmd.speed_mps, cmd.steering_rad, dt);
      const bool publish = i % steps_per_publish == 0, show = print && i % steps_per_print == 0;
      if (publish || show) {
        const SensorFrame f = robot.sense();
        if (publish) {
          for (auto& s : sinks) s->publish(f);
          odo.update(f.ticks[0], f.ticks[1]);
        }
        if (show) print_frame(f, odo.pose());
      }
      if (!fast) {
        next += std::chrono::duration_cast<std::chrono::steady_clock::duration>(std::chrono::duration<double>(dt));
        std::this_thread::sleep_until(next);
      }
    }
  } catch (const std::exception& e) {
    std::fprintf(stderr, "robot-sim: %s\n", e.what());
    return 1;
  }
  return 0;
}
