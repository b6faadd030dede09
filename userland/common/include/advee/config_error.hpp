// SPDX-License-Identifier: GPL-2.0
// The one error type of every configuration file of the stack (module YAML,
// the robot simulator's map and robot files, advee-rs485-sim's buses): a file that
// cannot be used. what() is "FILE:LINE: FIELD: what is wrong", or "FILE:
// what is wrong" for the file as a whole; a program prints it and exits
// (docs/command-line.md).
#pragma once

#include <stdexcept>
#include <string>
#include <string_view>

namespace advee {

class ConfigError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

// Throws the ConfigError for `field` at `line` (0-based, as yaml-cpp's
// Mark gives it; negative: no line known). An empty field is left out.
[[noreturn]] inline void throw_config_error(const std::string& file, int line, std::string_view field,
                                            std::string_view what) {
  std::string msg = file;
  if (line >= 0) msg += ":" + std::to_string(line + 1);
  msg += ": ";
  if (!field.empty()) (msg += field) += ": ";
  msg += what;
  throw ConfigError(msg);
}

}  // namespace advee
