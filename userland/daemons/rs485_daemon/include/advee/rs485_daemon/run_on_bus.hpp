// SPDX-License-Identifier: GPL-2.0
// The main loop of a module that owns one RS-485 bus (driver_rs485,
// driver_power): open the bus, build the driver on it, run the module.
#pragma once

#include <memory>
#include <optional>
#include <string>
#include <system_error>

#include "advee/rs485_daemon/node_health.hpp"
#include "advee/module/module.hpp"
#include "advee/rs485/bus.hpp"

namespace advee::rs485_daemon {

// A bus that cannot be opened is reported and ends the module with device
// error `no_bus_detail`; a ModuleExit from the driver is reported and ends it
// with its code. make_driver(rs485::Bus&, NodeStatusFn) returns the driver,
// which must live while the module runs.
template <typename MakeDriver>
int run_on_bus(module::Module& m, const std::string& device, const rs485::BusConfig& config,
               int no_bus_detail, MakeDriver make_driver) {
  std::unique_ptr<rs485::Bus> bus;
  try {
    rs485::BusOptions o;
    o.config = config;
    bus = std::make_unique<rs485::Bus>(device, o);
  } catch (const std::system_error& e) {
    const module::ModuleExit ex(module::ExitKind::Device, no_bus_detail,
                                "bus " + device + ": " + e.what());
    m.errors().report(module::Severity::Error, module::ErrorType::Device, ex.code(), ex.what(), true);
    return ex.code();
  }
  // The kernel's node error state; none while the bus is gone.
  NodeStatusFn status = [b = bus.get()](std::uint8_t addr) -> std::optional<rs485::NodeStatus> {
    try {
      return b->node(addr);
    } catch (const std::system_error&) {
      return std::nullopt;
    }
  };
  try {
    auto driver = make_driver(*bus, status);
    return m.run();
  } catch (const module::ModuleExit& e) {
    m.errors().report(module::Severity::Error, module::ErrorType::Device, e.code(), e.what(), true);
    return e.code();
  }
}

}  // namespace advee::rs485_daemon
