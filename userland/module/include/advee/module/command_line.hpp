// SPDX-License-Identifier: GPL-2.0
// The command line every robot module shares: [--config FILE] and --help,
// with the exit-code convention in the help text. One implementation so that
// the modules behave alike when the supervisor or an operator starts them.
#pragma once

#include <string>
#include <variant>

namespace advee::module {

struct CommandLineSpec {
  std::string name;            // program name, e.g. "driver_aux"
  std::string description;     // what it does: channels, devices; shown by --help
  std::string default_config;  // used when --config is absent and the file exists
  bool config_required = false;
  std::string exit_details;    // module-specific exit codes, one per line, for --help
};

// The configuration file to load ("" = the built-in defaults), or the status
// to exit with (advee/cli.hpp): 0 after --help or --version, 2 after a usage
// error (the message is on stderr).
std::variant<std::string, int> parse_command_line(const CommandLineSpec& spec, int argc,
                                                  char** argv);

}  // namespace advee::module
