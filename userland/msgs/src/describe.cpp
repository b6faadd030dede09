// SPDX-License-Identifier: GPL-2.0
#include "advee/msgs/describe.hpp"

#include <chrono>
#include <cstdint>
#include <cstdio>
#include <sstream>

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
#include "sim/data_pose_t.hpp"

namespace advee::msgs {
namespace {

double mono_s() {
  return std::chrono::duration<double>(std::chrono::steady_clock::now().time_since_epoch()).count();
}

std::int64_t utime_now() {
  return std::chrono::duration_cast<std::chrono::microseconds>(std::chrono::system_clock::now().time_since_epoch())
      .count();
}

template <typename Msg>
bool decode(const lcm::ReceiveBuffer& rb, Msg& m) {
  return m.decode(rb.data, 0, static_cast<int>(rb.data_size)) >= 0;
}

std::string num(double v, const char* fmt = "%.4f") {
  char b[48];
  std::snprintf(b, sizeof b, fmt, v);
  return b;
}

// One token for a key=value line.
std::string word(std::string s) {
  for (char& c : s)
    if (c == ' ' || c == '\n' || c == '\t') c = '_';
  return s.empty() ? "-" : s;
}

}  // namespace

std::string describe(const lcm::ReceiveBuffer& rb, const std::string& ch) {
  std::ostringstream o;
  o << ch << " t=" << num(mono_s(), "%.3f");
  if (common::data_state_t m; ch == "CM_DATA_STATE" && decode(rb, m)) {
    o << " module=" << m.module << " state=" << int(m.state) << " pid=" << m.pid;
  } else if (common::cmd_state_t m; ch == "CM_CMD_STATE" && decode(rb, m)) {
    o << " module=" << m.module << " target=" << m.target << " state=" << int(m.state) << " manual=" << int(m.manual);
  } else if (common::error_t m; ch == "CM_DATA_ERROR" && decode(rb, m)) {
    o << " module=" << m.module << " number=" << m.number << " severity=" << int(m.severity)
      << " fatal=" << int(m.fatal) << " text=" << word(m.text);
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
    // rx_us and age_us: the stop event's latency matters (sender to here).
    const std::int64_t rx = utime_now();
    o << " module=" << m.module << " stop=" << int(m.stop) << " source=" << int(m.source) << " age_us=" << (rx - m.utime)
      << " rx_us=" << rx;
  } else if (lowlevel::data_temperature_t m; ch == "LL_DATA_TEMPERATURE" && decode(rb, m)) {
    o << " module=" << m.module << " count=" << m.count;
    for (int i = 0; i < m.count; ++i) o << " " << word(m.label[i]) << "=" << num(m.celsius[i], "%.3f");
  } else if (lowlevel::data_fans_t m; ch == "LL_DATA_FANS" && decode(rb, m)) {
    o << " module=" << m.module << " count=" << m.count << " fan_fail=" << int(m.fan_fail);
    for (int i = 0; i < m.count; ++i) o << " " << word(m.label[i]) << "=" << m.rpm[i];
  } else if (lowlevel::data_drives_t m; ch == "LL_DATA_DRIVES" && decode(rb, m)) {
    o << " module=" << m.module << " speed=" << num(m.speed_mps) << " steering=" << num(m.steering_rad)
      << " cmd_speed=" << num(m.cmd_speed_mps) << " cmd_steering=" << num(m.cmd_steering_rad)
      << " stopped=" << int(m.stopped) << " reason=" << word(m.stop_reason) << " drives=" << m.num_drives;
    for (int i = 0; i < m.num_drives; ++i) {
      const int n = m.node[i];
      o << " node" << n << "=" << word(m.state[i]) << " fault" << n << "=" << int(m.fault[i]) << " emcy" << n << "="
        << m.error_code[i] << " homed" << n << "=" << int(m.homed[i]);
    }
  } else if (sim::data_pose_t m; ch == kSimDataPose && decode(rb, m)) {
    o << " module=advee-robot-sim sim_t=" << num(m.sim_time_s, "%.2f") << " x=" << num(m.x_m) << " y=" << num(m.y_m)
      << " heading=" << num(m.heading_rad) << " speed=" << num(m.speed_mps) << " steering=" << num(m.steering_rad)
      << " pause_sources=" << int(m.pause_sources) << " pause=" << int(m.pause_engaged)
      << " ticks_left=" << m.ticks_left << " ticks_right=" << m.ticks_right;
  } else {
    o << " undecoded bytes=" << rb.data_size;
  }
  return o.str();
}

}  // namespace advee::msgs
