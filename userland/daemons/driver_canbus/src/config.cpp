// SPDX-License-Identifier: GPL-2.0
#include "advee/driver_canbus/config.hpp"

#include "advee/canopen/device_description.hpp"
#include "advee/canopen/node_boot.hpp"

#include <cmath>
#include <filesystem>
#include <numbers>

namespace advee::driver_canbus {

using module::ConfigNode;

namespace {

unsigned node_id(const ConfigNode& n, unsigned fallback) {
  const auto id = n.get<unsigned>("node", fallback);
  if (id < 1 || id > 127) n.fail("node", "CANopen node-ID must be 1..127");
  return id;
}

// The drive's device description (EDS or DCF; relative to the configuration
// file): its identity is checked and its ParameterValue objects downloaded
// before the driver's own boot (CiA 302-2 style, canopen::NodeBoot).
void parse_device(const ConfigNode& n, unsigned node, canopen::DriveConfig& d) {
  if (!n.has("dcf")) return;
  std::filesystem::path path = n.get<std::string>("dcf", "");
  if (path.is_relative()) path = std::filesystem::path(n.file()).parent_path() / path;
  const auto r = canopen::load_device_description(path.string(), static_cast<std::uint8_t>(node));
  if (!r.description) {
    std::string why = "device description not usable:";
    for (const auto& e : r.errors) why += "\n  " + e.text();
    n.fail("dcf", why);
  }
  d.device = canopen::boot_config_from_dcf(*r.description, d.name);
}

// The keys both drives share: heartbeats, SDO timeout, PDO remapping, device description.
void parse_drive_common(const ConfigNode& n, unsigned node, canopen::DriveConfig& d) {
  parse_device(n, node, d);
  const auto hb = n.get<unsigned>("heartbeat_ms", d.heartbeat_ms);
  if (hb < 10 || hb > 10000) n.fail("heartbeat_ms", "must be 10..10000");
  d.heartbeat_ms = static_cast<std::uint16_t>(hb);
  const auto mt = n.get<unsigned>("master_timeout_ms", d.master_heartbeat_timeout_ms);
  if (mt > 60000) n.fail("master_timeout_ms", "must be 0..60000 (0: the drive does not watch the master)");
  d.master_heartbeat_timeout_ms = static_cast<std::uint16_t>(mt);
  const auto sdo = n.get<unsigned>("sdo_timeout_ms", 500);
  if (sdo < 10 || sdo > 10000) n.fail("sdo_timeout_ms", "must be 10..10000");
  d.sdo_timeout = std::chrono::milliseconds(sdo);
  d.remap_if_different = n.get<bool>("remap_pdos", d.remap_if_different);
}

std::uint32_t positive_u32(const ConfigNode& n, std::string_view key, std::uint32_t fallback) {
  const double v = n.get<double>(key, fallback);
  if (!(v >= 1 && v <= 4e9)) n.fail(key, "must be 1..4000000000");
  return static_cast<std::uint32_t>(std::lround(v));
}

void parse_propulsion(const ConfigNode& n, ControllerConfig& c) {
  n.allow_only({"node", "wheel_radius_m", "gear_ratio", "max_speed_mps", "acceleration_rpm_s", "deceleration_rpm_s",
                "quick_stop_deceleration_rpm_s", "heartbeat_ms", "master_timeout_ms", "sdo_timeout_ms",
                "remap_pdos", "dcf"});
  auto& e = c.epos;
  e.node = static_cast<std::uint8_t>(node_id(n, e.node));
  e.wheel_radius_m = n.get<double>("wheel_radius_m", e.wheel_radius_m);
  if (!(e.wheel_radius_m > 0.01 && e.wheel_radius_m < 2)) n.fail("wheel_radius_m", "must be 0.01..2");
  e.gear_ratio = n.get<double>("gear_ratio", e.gear_ratio);
  if (!(e.gear_ratio > 0 && e.gear_ratio <= 1000)) n.fail("gear_ratio", "must be > 0 and <= 1000");
  c.max_speed_mps = n.get<double>("max_speed_mps", c.max_speed_mps);
  if (!(c.max_speed_mps > 0 && c.max_speed_mps <= 20)) n.fail("max_speed_mps", "must be > 0 and <= 20");
  e.acceleration_rpm_s = positive_u32(n, "acceleration_rpm_s", e.acceleration_rpm_s);
  e.deceleration_rpm_s = positive_u32(n, "deceleration_rpm_s", e.deceleration_rpm_s);
  e.quick_stop_deceleration_rpm_s = positive_u32(n, "quick_stop_deceleration_rpm_s", e.quick_stop_deceleration_rpm_s);
  parse_drive_common(n, e.node, e.drive);
}

void parse_steering(const ConfigNode& n, ControllerConfig& c) {
  n.allow_only({"node", "units_per_rad", "limit_deg", "profile_velocity", "acceleration", "deceleration", "homing",
                "heartbeat_ms",
                "master_timeout_ms", "sdo_timeout_ms", "remap_pdos", "dcf"});
  auto& i = c.icla;
  i.node = static_cast<std::uint8_t>(node_id(n, i.node));
  i.units_per_rad = n.get<double>("units_per_rad", i.units_per_rad);
  if (!(std::abs(i.units_per_rad) >= 1 && std::abs(i.units_per_rad) <= 1e8))
    n.fail("units_per_rad", "magnitude must be 1..1e8 (negative: the drive counts right positive)");
  const double limit_deg = n.get<double>("limit_deg", c.steering_limit_rad * 180.0 / std::numbers::pi);
  if (!(limit_deg > 0 && limit_deg <= 90)) n.fail("limit_deg", "must be > 0 and <= 90");
  c.steering_limit_rad = limit_deg * std::numbers::pi / 180.0;
  i.profile_velocity = positive_u32(n, "profile_velocity", i.profile_velocity);
  c.steering_acceleration = positive_u32(n, "acceleration", c.steering_acceleration);
  c.steering_deceleration = positive_u32(n, "deceleration", c.steering_deceleration);
  if (n.has("homing")) {
    const auto h = n.child("homing");
    h.allow_only({"method", "speed", "acceleration", "offset", "timeout_s"});
    const int method = h.get<int>("method", i.homing_method);
    if (method < -128 || method > 127) h.fail("method", "CiA 402 homing method is an INT8");
    i.homing_method = static_cast<std::int8_t>(method);
    i.homing_speed = positive_u32(h, "speed", i.homing_speed);
    i.homing_acceleration = positive_u32(h, "acceleration", i.homing_acceleration);
    i.home_offset = h.get<int>("offset", i.home_offset);
    i.drive.homing_timeout = h.get_seconds("timeout_s", std::chrono::duration_cast<std::chrono::milliseconds>(
                                                            i.drive.homing_timeout),
                                           0.1, 600);
  }
  parse_drive_common(n, i.node, i.drive);
}

}  // namespace

CanbusConfig parse_canbus_config(const ConfigNode& root) {
  root.allow_only({"module", "driver_canbus"});
  CanbusConfig c;
  c.module.name = "driver_canbus";
  // The robot's drive units (common brief): 26:1 gear on 0.125 m wheels,
  // 10000 IclA units per steering radian; profile velocity 2 rad/s.
  c.controller.epos.wheel_radius_m = 0.125;
  c.controller.epos.gear_ratio = 26.0;
  c.controller.icla.units_per_rad = 10000.0;
  c.controller.icla.profile_velocity = 20000;
  c.controller.icla.homing_speed = 4000;
  c.controller.icla.homing_acceleration = 10000;
  c.controller.epos.drive.name = "epos";
  c.controller.icla.drive.name = "icla";
  if (root.has("module")) module::parse_module_options(root.child("module"), c.module);
  if (!root.has("driver_canbus")) return c;
  const auto n = root.child("driver_canbus");
  n.allow_only({"interface", "master", "publish_hz", "command_timeout_s", "retry_s", "home_on_start", "propulsion",
                "steering"});
  c.interface = n.get<std::string>("interface", c.interface);
  if (c.interface.empty() || c.interface.size() > 15) n.fail("interface", "must be a network interface name (1..15 characters)");
  if (n.has("master")) {
    const auto m = n.child("master");
    m.allow_only({"node_id", "heartbeat_ms"});
    const auto id = m.get<unsigned>("node_id", c.master_node);
    if (id < 1 || id > 127) m.fail("node_id", "CANopen node-ID must be 1..127");
    c.master_node = static_cast<std::uint8_t>(id);
    const auto hb = m.get<unsigned>("heartbeat_ms", static_cast<unsigned>(c.master_heartbeat.count()));
    if (hb > 10000) m.fail("heartbeat_ms", "must be 0..10000 (0: no master heartbeat)");
    c.master_heartbeat = std::chrono::milliseconds(hb);
  }
  c.publish_hz = n.get<double>("publish_hz", c.publish_hz);
  if (!(c.publish_hz >= 0.1 && c.publish_hz <= 50)) n.fail("publish_hz", "must be between 0.1 and 50");
  c.controller.command_timeout = n.get_seconds("command_timeout_s", std::chrono::milliseconds(1000), 0.05, 60);
  c.controller.retry = n.get_seconds("retry_s", std::chrono::milliseconds(2000), 0.1, 600);
  c.controller.home_on_start = n.get<bool>("home_on_start", c.controller.home_on_start);
  if (n.has("propulsion")) parse_propulsion(n.child("propulsion"), c.controller);
  if (n.has("steering")) parse_steering(n.child("steering"), c.controller);
  if (c.controller.epos.node == c.controller.icla.node)
    n.fail("steering", "propulsion and steering need different node-IDs");
  if (c.master_node == c.controller.epos.node || c.master_node == c.controller.icla.node)
    n.fail("master", "the master's node-ID must differ from the drives'");
  return c;
}

}  // namespace advee::driver_canbus
