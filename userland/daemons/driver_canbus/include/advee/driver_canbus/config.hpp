// SPDX-License-Identifier: GPL-2.0
// driver_canbus's configuration: the CAN interface, the master's heartbeat,
// the two drives (node-IDs, units, ramps, limits), the motion-command
// timeout and the homing of the steering. Defaults are the robot's
// (docs/daemons.md, conf/driver_canbus.yaml).
#pragma once

#include <chrono>
#include <cstdint>
#include <string>

#include "advee/canopen/drivers/epos.hpp"
#include "advee/canopen/drivers/icla.hpp"
#include "advee/module/config.hpp"

namespace advee::driver_canbus {

struct ControllerConfig {
  canopen::drivers::EposConfig epos;  // propulsion (node 1)
  canopen::drivers::IclaConfig icla;  // steering (node 2)
  double max_speed_mps = 2.0;         // |speed| above this is clamped (warning)
  double steering_limit_rad = 30.0 * 3.14159265358979323846 / 180.0;
  canopen::Duration command_timeout = std::chrono::seconds(1);  // no LL_CMD_MOTION: quick stop
  canopen::Duration retry = std::chrono::seconds(2);  // re-boot / re-enable attempts at most this often
  // IclA profile acceleration / deceleration (0x6083 / 0x6084), units/s^2,
  // written after its boot (the IclA driver writes only the velocity).
  std::uint32_t steering_acceleration = 100000;
  std::uint32_t steering_deceleration = 100000;
  bool home_on_start = false;  // home the steering whenever the IclA (re)boots
};

struct CanbusConfig {
  module::ModuleOptions module;
  std::string interface = "can0";
  std::uint8_t master_node = 0x7F;
  std::chrono::milliseconds master_heartbeat{100};
  double publish_hz = 4.0;  // LL_DATA_DRIVES
  ControllerConfig controller;
};

// Throws module::ConfigError ("file:line: key: what").
CanbusConfig parse_canbus_config(const module::ConfigNode& root);

}  // namespace advee::driver_canbus
