// SPDX-License-Identifier: GPL-2.0
// Reading the map and robot files: every error names the file, the line and
// the field (e.g. "room.yaml:12: obstacles[1].radius: must be > 0").
#pragma once

#include <yaml-cpp/yaml.h>

#include <string>

#include "advee/robotsim/geometry.hpp"
#include "advee/robotsim/world.hpp"

namespace advee::robotsim::yaml {

struct Ctx {
  std::string file;
  [[noreturn]] void fail(const YAML::Node& at, const std::string& field, const std::string& what) const;
};

// The document of a file or text; syntax errors become ConfigError with the line.
YAML::Node parse(const std::string& text, const std::string& name);
std::string read_file(const std::string& path);

// A required child; absent -> ConfigError "FIELD: missing" at the parent's line.
YAML::Node need(const Ctx& c, const YAML::Node& parent, const std::string& key, const std::string& field);
double number(const Ctx& c, const YAML::Node& n, const std::string& field);
double number_or(const Ctx& c, const YAML::Node& parent, const std::string& key, const std::string& field,
                 double fallback);
long integer(const Ctx& c, const YAML::Node& n, const std::string& field, long min, long max);
Vec2 point(const Ctx& c, const YAML::Node& n, const std::string& field);

}  // namespace advee::robotsim::yaml
