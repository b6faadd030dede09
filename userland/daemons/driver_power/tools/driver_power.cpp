// SPDX-License-Identifier: GPL-2.0
// driver_power [--config FILE]: the BR-PSC1 power controller on LCM
// (docs/daemons.md).
#include <iostream>
#include <memory>
#include <string>
#include <variant>

#include "advee/module/command_line.hpp"
#include "advee/driver_power/power_driver.hpp"
#include "advee/rs485/bus.hpp"

using namespace advee;

int main(int argc, char** argv) {
  return module::guarded_main("driver_power", [&] {
    module::CommandLineSpec spec;
    spec.name = "driver_power";
    spec.description = "Publishes the BR-PSC1 output status and currents (LL_DATA_POWER), forwards\n"
                       "its PAUSE events (LL_EVENT_STOP), obeys LL_CMD_POWER; see docs/daemons.md.";
    spec.default_config = "/etc/advee/driver_power.yaml";
    spec.exit_details = "  0x21       the bus cannot be opened or configured\n";
    const auto args = module::parse_command_line(spec, argc, argv);
    if (const int* status = std::get_if<int>(&args)) return *status;
    const std::string& config = std::get<std::string>(args);
    const auto cfg = config.empty()
                         ? driver_power::parse_power_config(module::ConfigNode::parse("{}", "defaults"))
                         : driver_power::parse_power_config(module::ConfigNode::load_file(config));
    module::Module m(cfg.module);  // first: the bus's event thread inherits the blocked signals
    std::unique_ptr<rs485::Bus> bus;
    try {
      rs485::BusOptions o;
      o.config = rs485::BusConfig{cfg.baud, cfg.timeout, cfg.retries, 2};
      bus = std::make_unique<rs485::Bus>(cfg.device, o);
    } catch (const std::system_error& e) {
      const module::ModuleExit ex(module::ExitKind::Device, driver_power::kExitNoBus,
                                  "bus " + cfg.device + ": " + e.what());
      m.errors().report(module::Severity::Error, module::ErrorType::Device, ex.code(), ex.what(), true);
      return ex.code();
    }
    auto status = [b = bus.get()](std::uint8_t addr) -> std::optional<rs485::NodeStatus> {
      try {
        return b->node(addr);
      } catch (const std::system_error&) {
        return std::nullopt;
      }
    };
    int code = 0;
    try {
      driver_power::PowerDriver driver(m, cfg, *bus, status);
      code = m.run();
    } catch (const module::ModuleExit& e) {
      m.errors().report(module::Severity::Error, module::ErrorType::Device, e.code(), e.what(), true);
      return e.code();
    }
    return code;
  });
}
