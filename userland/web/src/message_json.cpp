// SPDX-License-Identifier: GPL-2.0
#include "advee/web/message_json.hpp"

#include <cmath>
#include <functional>
#include <map>

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
#define ADVEE_WEB_HAVE_SIM_POSE 1
#endif

namespace advee::web {
namespace {

using nlohmann::json;

// JSON has no NaN or infinity: a missing reading becomes null.
json number(double v) { return std::isfinite(v) ? json(v) : json(nullptr); }

template <typename T>
json numbers(const std::vector<T>& v) {
  json a = json::array();
  for (const auto& x : v) {
    if constexpr (std::is_floating_point_v<T>)
      a.push_back(number(x));
    else
      a.push_back(x);
  }
  return a;
}

// LCM's boolean arrays are int8_t vectors; the page wants true/false.
json bools(const std::vector<std::int8_t>& v) {
  json a = json::array();
  for (auto x : v) a.push_back(x != 0);
  return a;
}

json strings(const std::vector<std::string>& v) { return json(v); }

json base(std::string_view channel, std::int64_t utime, const std::string& module) {
  return json{{"channel", channel}, {"utime", utime}, {"module", module}};
}

json fields(std::string_view ch, const common::data_state_t& m) {
  json j = base(ch, m.utime, m.module);
  j["state"] = m.state;
  j["pid"] = m.pid;
  return j;
}

json fields(std::string_view ch, const common::cmd_state_t& m) {
  json j = base(ch, m.utime, m.module);
  j["target"] = m.target;
  j["state"] = m.state;
  j["manual"] = m.manual != 0;
  return j;
}

json fields(std::string_view ch, const common::error_t& m) {
  json j = base(ch, m.utime, m.module);
  j["number"] = m.number;
  j["text"] = m.text;
  j["fatal"] = m.fatal != 0;
  j["type"] = m.type;
  j["severity"] = m.severity;
  j["file"] = m.file;
  j["line"] = m.line;
  return j;
}

json fields(std::string_view ch, const common::data_module_phase_t& m) {
  json j = base(ch, m.utime, m.module);
  j["target"] = m.target;
  j["phase"] = m.phase;
  j["pid"] = m.pid;
  j["restarts"] = m.restarts;
  j["exit_status"] = m.exit_status;
  j["next_start_ms"] = m.next_start_ms;
  j["command"] = m.command;
  return j;
}

json fields(std::string_view ch, const lowlevel::data_srfs_t& m) {
  json j = base(ch, m.utime, m.module);
  j["srf_id"] = numbers(m.srf_id);
  j["srf_range_m"] = numbers(m.srf_range_m);
  j["ir_id"] = numbers(m.ir_id);
  j["ir_range_m"] = numbers(m.ir_range_m);
  return j;
}

json fields(std::string_view ch, const lowlevel::data_odo_t& m) {
  json j = base(ch, m.utime, m.module);
  j["ticks_left"] = m.ticks_left;
  j["ticks_right"] = m.ticks_right;
  j["interval_s"] = number(m.interval_s);
  j["speed_mps"] = number(m.speed_mps);
  j["yaw_rate_radps"] = number(m.yaw_rate_radps);
  return j;
}

json fields(std::string_view ch, const lowlevel::data_beacons_t& m) {
  json j = base(ch, m.utime, m.module);
  j["id"] = numbers(m.id);
  j["bearing_rad"] = numbers(m.bearing_rad);
  return j;
}

json fields(std::string_view ch, const lowlevel::data_active_beacons_t& m) {
  json j = base(ch, m.utime, m.module);
  j["id"] = numbers(m.id);
  return j;
}

json fields(std::string_view ch, const lowlevel::cmd_motion_t& m) {
  json j = base(ch, m.utime, m.module);
  j["speed_mps"] = number(m.speed_mps);
  j["steering_rad"] = number(m.steering_rad);
  return j;
}

json fields(std::string_view ch, const lowlevel::cmd_homing_t& m) {
  json j = base(ch, m.utime, m.module);
  j["axis"] = m.axis;
  return j;
}

json fields(std::string_view ch, const lowlevel::cmd_power_t& m) {
  json j = base(ch, m.utime, m.module);
  j["action"] = m.action;
  j["output"] = m.output;
  j["on"] = m.on != 0;
  return j;
}

json fields(std::string_view ch, const lowlevel::data_power_t& m) {
  json j = base(ch, m.utime, m.module);
  j["battery_v"] = number(m.battery_v);
  j["on"] = bools(m.on);
  j["current_a"] = numbers(m.current_a);
  j["paused"] = m.paused != 0;
  return j;
}

json fields(std::string_view ch, const lowlevel::event_stop_t& m) {
  json j = base(ch, m.utime, m.module);
  j["stop"] = m.stop != 0;
  j["source"] = m.source;
  return j;
}

json fields(std::string_view ch, const lowlevel::data_temperature_t& m) {
  json j = base(ch, m.utime, m.module);
  j["label"] = strings(m.label);
  j["celsius"] = numbers(m.celsius);
  return j;
}

json fields(std::string_view ch, const lowlevel::data_fans_t& m) {
  json j = base(ch, m.utime, m.module);
  j["label"] = strings(m.label);
  j["rpm"] = numbers(m.rpm);
  j["fault"] = bools(m.fault);
  j["fan_fail"] = m.fan_fail != 0;
  j["pwm"] = numbers(m.pwm);
  return j;
}

json fields(std::string_view ch, const lowlevel::data_drives_t& m) {
  json j = base(ch, m.utime, m.module);
  j["axis"] = numbers(m.axis);
  j["node"] = numbers(m.node);
  j["state"] = strings(m.state);
  j["fault"] = bools(m.fault);
  j["error_code"] = numbers(m.error_code);
  j["homed"] = bools(m.homed);
  j["speed_mps"] = number(m.speed_mps);
  j["steering_rad"] = number(m.steering_rad);
  j["cmd_speed_mps"] = number(m.cmd_speed_mps);
  j["cmd_steering_rad"] = number(m.cmd_steering_rad);
  j["stopped"] = m.stopped != 0;
  j["stop_reason"] = m.stop_reason;
  return j;
}

#ifdef ADVEE_WEB_HAVE_SIM_POSE
json fields(std::string_view ch, const sim::data_pose_t& m) {
  json j{{"channel", ch}, {"utime", m.utime}};
  j["sim_time_s"] = number(m.sim_time_s);
  j["x_m"] = number(m.x_m);
  j["y_m"] = number(m.y_m);
  j["heading_rad"] = number(m.heading_rad);
  j["speed_mps"] = number(m.speed_mps);
  j["steering_rad"] = number(m.steering_rad);
  j["pause_sources"] = m.pause_sources;
  j["pause_engaged"] = m.pause_engaged != 0;
  j["ticks_left"] = m.ticks_left;
  j["ticks_right"] = m.ticks_right;
  return j;
}
#endif

using Decoder = std::function<std::optional<json>(std::string_view, const void*, std::size_t)>;

template <typename T>
Decoder decoder() {
  return [](std::string_view ch, const void* data, std::size_t size) -> std::optional<json> {
    T m{};
    // decode() returns the bytes consumed; a message must be consumed whole.
    if (m.decode(data, 0, static_cast<int>(size)) != static_cast<int>(size)) return std::nullopt;
    return fields(ch, m);
  };
}

const std::map<std::string, Decoder, std::less<>>& decoders() {
  namespace msgs = advee::msgs;
  static const std::map<std::string, Decoder, std::less<>> table{
      {std::string(msgs::kDataState.name), decoder<common::data_state_t>()},
      {std::string(msgs::kCmdState.name), decoder<common::cmd_state_t>()},
      {std::string(msgs::kDataError.name), decoder<common::error_t>()},
      {std::string(msgs::kDataModules.name), decoder<common::data_module_phase_t>()},
      {std::string(msgs::kDataSrfs.name), decoder<lowlevel::data_srfs_t>()},
      {std::string(msgs::kDataOdo.name), decoder<lowlevel::data_odo_t>()},
      {std::string(msgs::kDataBeacons.name), decoder<lowlevel::data_beacons_t>()},
      {std::string(msgs::kDataActiveBeacons.name), decoder<lowlevel::data_active_beacons_t>()},
      {std::string(msgs::kCmdMotion.name), decoder<lowlevel::cmd_motion_t>()},
      {std::string(msgs::kCmdHoming.name), decoder<lowlevel::cmd_homing_t>()},
      {std::string(msgs::kCmdPower.name), decoder<lowlevel::cmd_power_t>()},
      {std::string(msgs::kDataPower.name), decoder<lowlevel::data_power_t>()},
      {std::string(msgs::kEventStop.name), decoder<lowlevel::event_stop_t>()},
      {std::string(msgs::kDataTemperature.name), decoder<lowlevel::data_temperature_t>()},
      {std::string(msgs::kDataFans.name), decoder<lowlevel::data_fans_t>()},
      {std::string(msgs::kDataDrives.name), decoder<lowlevel::data_drives_t>()},
#ifdef ADVEE_WEB_HAVE_SIM_POSE
      {std::string(kSimPoseChannel), decoder<sim::data_pose_t>()},
#endif
  };
  return table;
}

}  // namespace

std::vector<std::string> bridged_channels() {
  std::vector<std::string> out;
  for (const auto& [name, d] : decoders()) out.push_back(name);
  return out;
}

std::optional<nlohmann::json> message_to_json(std::string_view channel, const void* data,
                                              std::size_t size) {
  const auto& table = decoders();
  const auto it = table.find(channel);
  if (it == table.end()) return std::nullopt;
  return it->second(channel, data, size);
}

std::string replace_key(const nlohmann::json& message) {
  std::string key = message.value("channel", "");
  if (key == msgs::kDataModules.name || key == msgs::kCmdState.name)
    return key + "/" + message.value("target", "");
  if (key == msgs::kDataState.name || key == msgs::kDataError.name)
    return key + "/" + message.value("module", "");
  return key;
}

}  // namespace advee::web
