// SPDX-License-Identifier: GPL-2.0
// driver_power [--config FILE]: the BR-PSC1 power controller on LCM
// (docs/daemons.md).
#include <iostream>
#include <memory>
#include <string>
#include <variant>

#include "advee/module/command_line.hpp"
#include "advee/driver_power/power_driver.hpp"
#include "advee/rs485_daemon/run_on_bus.hpp"

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
    return rs485_daemon::run_on_bus(
        m, cfg.bus.device, cfg.bus.config, driver_power::kExitNoBus, [&](rs485::Bus& bus, rs485_daemon::NodeStatusFn status) {
          return std::make_unique<driver_power::PowerDriver>(m, cfg, bus, std::move(status));
        });
  });
}
