// SPDX-License-Identifier: GPL-2.0
// driver_aux [--config FILE]: the auxiliary-devices module (docs/modules.md).
#include <iostream>
#include <string>

#include "advee/driver_aux/aux_driver.hpp"

using namespace advee;

int main(int argc, char** argv) {
  return module::guarded_main("driver_aux", [&] {
    std::string config;
    for (int i = 1; i < argc; ++i) {
      const std::string a = argv[i];
      if ((a == "-c" || a == "--config") && i + 1 < argc) {
        config = argv[++i];
      } else if (a == "-h" || a == "--help") {
        std::cout << "usage: driver_aux [--config FILE]\n"
                     "Publishes the MAX6615 temperatures (LL_DATA_TEMPERATURE) and fans\n"
                     "(LL_DATA_FANS) read from its hwmon device; see docs/modules.md.\n"
                     "Without --config: /etc/advee/driver_aux.yaml if present, else defaults.\n";
        return 0;
      } else {
        std::cerr << "driver_aux: unknown argument " << a << " (see --help)\n";
        return module::exit_code(module::ExitKind::Other, 1);
      }
    }
    if (config.empty() && std::filesystem::exists("/etc/advee/driver_aux.yaml"))
      config = "/etc/advee/driver_aux.yaml";
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
