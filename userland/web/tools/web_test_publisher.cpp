// SPDX-License-Identifier: GPL-2.0
// advee-web-test-publisher: a known set of messages on every bridged channel,
// for the dashboard's browser test (and to look at the page without a robot).
// The robot drives a left circle at 0.5 m/s for --drive seconds (odometry,
// true pose, ranges, beacons, drives, temperatures rising), then stands and
// holds the final values below until --hold runs out:
//   modules: driver_aux RUN, driver_rs485a RUN, driver_power PAUSE
//   temperatures: temp1 41.5 C, temp2 33.2 C; fans: fan1 2400 rpm
//   power: battery 24.6 V, paused; one CM_DATA_ERROR "test error: bus timeout"
#include <CLI/CLI.hpp>
#include <chrono>
#include <cmath>
#include <iostream>
#include <lcm/lcm-cpp.hpp>
#include <thread>

#include "advee/module/time.hpp"
#include "advee/msgs/channels.hpp"
#include "common/data_module_phase_t.hpp"
#include "common/data_state_t.hpp"
#include "common/error_t.hpp"
#include "lowlevel/cmd_motion_t.hpp"
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
#define ADVEE_WEB_HAVE_SIM_POSE 1
#endif

namespace {

using advee::module::utime_now;
namespace msgs = advee::msgs;
constexpr double kPi = 3.14159265358979323846;
constexpr double kSpeed = 0.5, kSteering = 0.3, kWheelbase = 0.62;

struct Pose {
  double x = 2.0, y = 2.0, heading = 0;
};

void publish_states(lcm::LCM& lcm, bool paused) {
  const struct {
    const char* name;
    std::int8_t state;
  } modules[] = {{"driver_aux", common::data_state_t::RUN},
                 {"driver_rs485a", common::data_state_t::RUN},
                 {"driver_power", paused ? common::data_state_t::PAUSE : common::data_state_t::RUN}};
  int pid = 1000;
  for (const auto& m : modules) {
    common::data_state_t s{};
    s.utime = utime_now();
    s.module = m.name;
    s.state = m.state;
    s.pid = ++pid;
    lcm.publish(std::string(msgs::kDataState.name), &s);
    common::data_module_phase_t p{};
    p.utime = s.utime;
    p.module = "advee-watchdog";
    p.target = m.name;
    p.phase = common::data_module_phase_t::RUNNING;
    p.pid = pid;
    p.restarts = m.name == std::string("driver_aux") ? 1 : 0;
    p.exit_status = -1;
    p.next_start_ms = -1;
    p.command = common::data_state_t::RUN;
    lcm.publish(std::string(msgs::kDataModules.name), &p);
  }
}

void publish_slow(lcm::LCM& lcm, double frac, bool paused) {
  publish_states(lcm, paused);
  lowlevel::data_temperature_t t{};
  t.utime = utime_now();
  t.module = "driver_aux";
  t.count = 2;
  t.label = {"temp1", "temp2"};
  t.celsius = {static_cast<float>(30 + 11.5 * frac), static_cast<float>(28 + 5.2 * frac)};
  lcm.publish(std::string(msgs::kDataTemperature.name), &t);
  lowlevel::data_fans_t f{};
  f.utime = t.utime;
  f.module = "driver_aux";
  f.count = 1;
  f.label = {"fan1"};
  f.rpm = {static_cast<std::int32_t>(1200 + 1200 * frac)};
  f.fault = {0};
  f.fan_fail = 0;
  f.pwm = {static_cast<std::int16_t>(100 + 100 * frac)};
  lcm.publish(std::string(msgs::kDataFans.name), &f);
  lowlevel::data_power_t p{};
  p.utime = t.utime;
  p.module = "driver_power";
  p.battery_v = 24.6f;
  p.num_outputs = 4;
  p.on = {1, 1, 0, 1};
  p.current_a = {1.25f, 0.5f, 0.0f, -1.0f};
  p.paused = paused;
  lcm.publish(std::string(msgs::kDataPower.name), &p);
}

void publish_fast(lcm::LCM& lcm, const Pose& pose, double speed, double steering, double dt) {
  const auto now = utime_now();
  lowlevel::data_odo_t o{};
  o.utime = now;
  o.module = "driver_rs485a";
  o.interval_s = dt;
  o.speed_mps = speed;
  o.yaw_rate_radps = speed * std::tan(steering) / kWheelbase;
  o.ticks_left = static_cast<std::int32_t>(speed * dt / (2 * kPi * 0.125) * 2048);
  o.ticks_right = o.ticks_left;
  lcm.publish(std::string(msgs::kDataOdo.name), &o);

  lowlevel::data_srfs_t s{};
  s.utime = now;
  s.module = "driver_rs485a";
  s.num_srfs = 16;
  for (int i = 0; i < 16; ++i) {
    s.srf_id.push_back(static_cast<std::int16_t>(i));
    // One sensor without an echo shows how the page draws "none".
    s.srf_range_m.push_back(i == 5 ? -1.0f : static_cast<float>(1.0 + 0.15 * i + 0.2 * std::sin(pose.heading + i)));
  }
  s.num_irs = 4;
  s.ir_id = {0, 1, 2, 3};
  s.ir_range_m = {0.12f, 0.121f, 0.119f, 0.12f};
  lcm.publish(std::string(msgs::kDataSrfs.name), &s);

  lowlevel::cmd_motion_t m{};
  m.utime = now;
  m.module = "advee-web-test-publisher";
  m.speed_mps = speed > 0 ? kSpeed : 0;
  m.steering_rad = steering;
  lcm.publish(std::string(msgs::kCmdMotion.name), &m);

  lowlevel::data_drives_t d{};
  d.utime = now;
  d.module = "driver_canbus";
  d.num_drives = 2;
  d.axis = {lowlevel::data_drives_t::AXIS_PROPULSION, lowlevel::data_drives_t::AXIS_STEERING};
  d.node = {1, 2};
  d.state = {"operation enabled", "operation enabled"};
  d.fault = {0, 0};
  d.error_code = {0, 0};
  d.homed = {0, 1};
  d.speed_mps = speed;
  d.steering_rad = steering;
  d.cmd_speed_mps = m.speed_mps;
  d.cmd_steering_rad = steering;
  d.stopped = speed == 0;
  d.stop_reason = speed == 0 ? "LL_EVENT_STOP" : "";
  lcm.publish(std::string(msgs::kDataDrives.name), &d);

#ifdef ADVEE_WEB_HAVE_SIM_POSE
  sim::data_pose_t p{};
  p.utime = now;
  p.sim_time_s = 0;
  p.x_m = pose.x;
  p.y_m = pose.y;
  p.heading_rad = std::remainder(pose.heading, 2 * kPi);
  p.speed_mps = speed;
  p.steering_rad = steering;
  p.pause_sources = 0;
  p.pause_engaged = speed == 0;
  lcm.publish(std::string("SIM_DATA_POSE"), &p);
#endif
}

void publish_beacons(lcm::LCM& lcm, const Pose& pose) {
  // Beacons of robotsim's room.yaml corners: true bearings from the pose.
  const double beacons[][3] = {{1, 0.05, 0.05}, {2, 9.95, 0.05}, {3, 9.95, 7.95}, {4, 0.05, 7.95}};
  lowlevel::data_beacons_t b{};
  b.utime = utime_now();
  b.module = "driver_rs485b";
  for (const auto& bc : beacons) {
    const double world = std::atan2(bc[2] - pose.y, bc[1] - pose.x);
    b.id.push_back(static_cast<std::int16_t>(bc[0]));
    b.bearing_rad.push_back(static_cast<float>(std::remainder(world - pose.heading, 2 * kPi)));
  }
  b.count = static_cast<std::int16_t>(b.id.size());
  lcm.publish(std::string(msgs::kDataBeacons.name), &b);
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{"advee-web-test-publisher: a known set of messages on every channel the dashboard "
               "shows (see the source's head comment for the final values)",
               "advee-web-test-publisher"};
  std::string url;
  double drive_s = 6, hold_s = 30, rate_hz = 10;
  app.add_option("--lcm", url, "LCM URL (default: LCM_DEFAULT_URL)");
  app.add_option("--drive", drive_s, "seconds of driving")->capture_default_str();
  app.add_option("--hold", hold_s, "seconds of holding the final values afterwards")->capture_default_str();
  app.add_option("--rate", rate_hz, "fast channels' rate, Hz")->capture_default_str()->check(CLI::Range(1.0, 100.0));
  CLI11_PARSE(app, argc, argv);

  lcm::LCM lcm(url);
  if (!lcm.good()) {
    std::cerr << "advee-web-test-publisher: cannot set up LCM\n";
    return 1;
  }
  const double dt = 1.0 / rate_hz;
  const int drive_steps = static_cast<int>(drive_s * rate_hz);
  const int total_steps = drive_steps + static_cast<int>(hold_s * rate_hz);
  Pose pose;
  auto next = std::chrono::steady_clock::now();
  for (int i = 0; i <= total_steps; ++i) {
    const bool driving = i < drive_steps;
    const double speed = driving ? kSpeed : 0, steering = driving ? kSteering : 0;
    publish_fast(lcm, pose, speed, steering, dt);
    const int per_s = static_cast<int>(rate_hz);
    if (i % per_s == 0 || i == drive_steps) {
      publish_slow(lcm, std::min(1.0, static_cast<double>(i) / std::max(drive_steps, 1)), !driving);
      publish_beacons(lcm, pose);
    }
    if (i == drive_steps) {
      lowlevel::event_stop_t e{};
      e.utime = utime_now();
      e.module = "driver_power";
      e.stop = 1;
      e.source = lowlevel::event_stop_t::SOURCE_PSC1;
      lcm.publish(std::string(msgs::kEventStop.name), &e);
      common::error_t err{};
      err.utime = e.utime;
      err.module = "driver_rs485a";
      err.number = 110;
      err.text = "test error: bus timeout";
      err.type = common::error_t::TYPE_TIMEOUT;
      err.severity = common::error_t::SEVERITY_WARNING;
      err.file = "web_test_publisher.cpp";
      err.line = __LINE__;
      lcm.publish(std::string(msgs::kDataError.name), &err);
    }
    // The pose the odometry describes: exact arc over dt.
    const double w = speed * std::tan(steering) / kWheelbase;
    if (std::abs(w) > 1e-12) {
      const double r = speed / w;
      pose.x += r * (std::sin(pose.heading + w * dt) - std::sin(pose.heading));
      pose.y -= r * (std::cos(pose.heading + w * dt) - std::cos(pose.heading));
    } else {
      pose.x += speed * dt * std::cos(pose.heading);
      pose.y += speed * dt * std::sin(pose.heading);
    }
    pose.heading += w * dt;
    next += std::chrono::microseconds(static_cast<long>(dt * 1e6));
    std::this_thread::sleep_until(next);
  }
  return 0;
}
