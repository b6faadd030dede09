// SPDX-License-Identifier: GPL-2.0
// The `bus:` section of an RS-485 daemon's configuration (driver_rs485,
// driver_power): the device and its n_rs485 settings, parsed in one place
// with one set of defaults.
#pragma once

#include <chrono>
#include <optional>
#include <string>

#include "advee/module/config.hpp"
#include "advee/rs485/bus.hpp"

namespace advee::rs485_daemon {

struct BusSection {
  std::string device;  // path, or bus name: /dev/rs485/NAME
  // The robot's boards answer within a few ms: 20 ms per attempt and one
  // retry (docs/daemons.md); baud and the idle gap are the kernel's
  // defaults. A daemon configures the bus with these (the kernel's bus
  // default becomes the daemon's timeout) and uses them per call.
  rs485::BusConfig config = robot_defaults();

  static rs485::BusConfig robot_defaults() {
    rs485::BusConfig c;
    c.timeout = std::chrono::milliseconds(20);
    c.retries = 1;
    return c;
  }
};

// Keys device, baud, timeout_ms, retries; device is required when there is
// no default_device, the others are optional. Ranges as the kernel checks
// them (rs485::BusConfig). Throws module::ConfigError naming file:line: key.
BusSection parse_bus_section(const module::ConfigNode& bus, const std::optional<std::string>& default_device);

}  // namespace advee::rs485_daemon
