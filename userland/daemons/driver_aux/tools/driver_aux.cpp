// SPDX-License-Identifier: GPL-2.0
// driver_aux [--config FILE]: the auxiliary-devices module (docs/modules.md).
#include <iostream>
#include <string>
#include <variant>

#include "advee/module/command_line.hpp"
#include "advee/driver_aux/aux_driver.hpp"

using namespace advee;

int main(int argc, char** argv) {
  return module::guarded_main("driver_aux", [&] {
    module::CommandLineSpec spec;
    spec.name = "driver_aux";
    spec.description = "Publishes the MAX6615 temperatures (LL_DATA_TEMPERATURE) and fan speeds\n"
                       "(LL_DATA_FANS) read from its hwmon device, watches the fan-fail line;\n"
                       "see docs/modules.md.";
    spec.default_config = "/etc/advee/driver_aux.yaml";
    spec.exit_details =
        "  0x21       no MAX6615 hwmon device\n  0x22       the device went away\n"
        "  0x23       the fan-fail line cannot be requested\n  0x24       a configured channel is missing\n";
    const auto args = module::parse_command_line(spec, argc, argv);
    if (const int* status = std::get_if<int>(&args)) return *status;
    const std::string& config = std::get<std::string>(args);
    auto cfg = config.empty() ? driver_aux::parse_aux_config(module::ConfigNode::parse("{}", "defaults"))
                              : driver_aux::parse_aux_config(module::ConfigNode::load_file(config));
    module::Module m(cfg.module);
    int code = 0;
    try {
      driver_aux::AuxDriver driver(m, cfg);
      code = m.run();
    } catch (const module::ModuleExit& e) {
      m.errors().report(module::Severity::Error, module::ErrorType::Device, e.code(), e.what(), true);
      return e.code();
    }
    return code;
  });
}
