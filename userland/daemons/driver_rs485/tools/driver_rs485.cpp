// SPDX-License-Identifier: GPL-2.0
// driver_rs485 --config FILE: polls the boards of one RS-485 bus and
// publishes their readings on LCM (docs/daemons.md). One instance per bus:
// /etc/advee/driver_rs485a.yaml (SD1 x2 + SO1, 4 Hz), driver_rs485b.yaml (SBS1, 1 Hz).
#include <iostream>
#include <memory>
#include <string>
#include <variant>

#include "advee/module/command_line.hpp"
#include "advee/driver_rs485/rs485_driver.hpp"
#include "advee/rs485_daemon/run_on_bus.hpp"

using namespace advee;

int main(int argc, char** argv) {
  return module::guarded_main("driver_rs485", [&] {
    module::CommandLineSpec spec;
    spec.name = "driver_rs485";
    spec.description = "Polls the BR-SD1/SO1/SBS1 boards of one RS-485 bus and publishes\n"
                       "LL_DATA_SRFS, LL_DATA_ODO and LL_DATA_BEACONS (beacon ids from\n"
                       "LL_DATA_ACTIVE_BEACONS); see docs/daemons.md. One instance per bus:\n"
                       "/etc/advee/driver_rs485a.yaml (bus A), /etc/advee/driver_rs485b.yaml (bus B).";
    spec.config_required = true;
    spec.exit_details = "  0x21       the bus cannot be opened or configured\n";
    const auto args = module::parse_command_line(spec, argc, argv);
    if (const int* status = std::get_if<int>(&args)) return *status;
    const std::string& config = std::get<std::string>(args);
    const auto cfg = driver_rs485::parse_rs485_config(module::ConfigNode::load_file(config));
    module::Module m(cfg.module);
    return rs485_daemon::run_on_bus(
        m, cfg.bus.device, cfg.bus.config, driver_rs485::kExitNoBus, [&](rs485::Bus& bus, rs485_daemon::NodeStatusFn status) {
          return std::make_unique<driver_rs485::Rs485Driver>(m, cfg, bus, std::move(status));
        });
  });
}
