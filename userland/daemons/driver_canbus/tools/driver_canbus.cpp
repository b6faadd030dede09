// SPDX-License-Identifier: GPL-2.0
// driver_canbus [--config FILE]: the CANopen drives (Maxon EPOS propulsion,
// Berger Lahr IclA steering) on LCM (docs/daemons.md).
#include <string>
#include <variant>

#include "advee/driver_canbus/canbus_driver.hpp"
#include "advee/module/command_line.hpp"

using namespace advee;

int main(int argc, char** argv) {
  return module::guarded_main("driver_canbus", [&] {
    module::CommandLineSpec spec;
    spec.name = "driver_canbus";
    spec.description =
        "Drives the robot over CANopen: LL_CMD_MOTION -> EPOS target velocity and IclA steering\n"
        "position, LL_CMD_HOMING, quick stop after 1 s without commands and on LL_EVENT_STOP;\n"
        "publishes LL_DATA_DRIVES at 4 Hz. See docs/daemons.md.";
    spec.default_config = "/etc/advee/driver_canbus.yaml";
    spec.exit_details =
        "  0x21       the CAN interface cannot be opened\n"
        "  0x22       a drive cannot be booted at start-up\n"
        "  0x23       the CAN loop failed (e.g. the interface went down)\n";
    const auto args = module::parse_command_line(spec, argc, argv);
    if (const int* status = std::get_if<int>(&args)) return *status;
    const std::string& config = std::get<std::string>(args);
    const auto cfg = driver_canbus::parse_canbus_config(
        config.empty() ? module::ConfigNode::parse("{}", "defaults") : module::ConfigNode::load_file(config));
    module::Module m(cfg.module);  // first: the CAN thread inherits the blocked signals
    driver_canbus::CanbusDriver driver(m, cfg);
    return m.run();
  });
}
