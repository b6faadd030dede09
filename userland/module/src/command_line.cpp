// SPDX-License-Identifier: GPL-2.0
#include "advee/module/command_line.hpp"

#include <CLI/CLI.hpp>
#include <filesystem>
#include <iostream>

#include "advee/cli.hpp"

namespace advee::module {

std::variant<std::string, int> parse_command_line(const CommandLineSpec& spec, int argc,
                                                  char** argv) {
  CLI::App app(spec.description, spec.name);
  std::string config;
  auto* opt = app.add_option("-c,--config", config, "YAML configuration file");
  if (spec.config_required)
    opt->required();
  else if (!spec.default_config.empty())
    opt->description("YAML configuration file (default: " + spec.default_config +
                     " if it exists, else built-in defaults)");
  std::string footer =
      "SIGNALS\n"
      "  SIGTERM, SIGINT: leave through the TERMINATE state and exit 0.\n"
      "  The state follows CM_CMD_STATE addressed to this module (docs/modules.md).\n\n"
      "EXIT STATUS\n"
      "  0          terminated on request\n"
      "  2          bad command line (nothing started)\n"
      "  0x10+N     resource error N (memory, files, LCM)\n"
      "  0x20+N     device error N\n"
      "  0x40+N     other error N; 0x41 = bad configuration\n";
  if (!spec.exit_details.empty()) footer += spec.exit_details;
  app.footer(footer);
  if (const auto status = cli::parse(app, argc, argv)) return *status;
  if (config.empty() && !spec.default_config.empty() &&
      std::filesystem::exists(spec.default_config))
    config = spec.default_config;
  return config;
}

}  // namespace advee::module
