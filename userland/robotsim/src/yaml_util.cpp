// SPDX-License-Identifier: GPL-2.0
#include "yaml_util.hpp"

#include <cmath>
#include <fstream>
#include <sstream>

namespace advee::robotsim::yaml {

void Ctx::fail(const YAML::Node& at, const std::string& field, const std::string& what) const {
  throw_config_error(file, at.Mark().line, field, what);
}

YAML::Node parse(const std::string& text, const std::string& name) {
  try {
    YAML::Node doc = YAML::Load(text);
    if (!doc.IsMap()) throw ConfigError(name + ": not a YAML mapping at the top level");
    return doc;
  } catch (const YAML::Exception& e) {
    throw_config_error(name, e.mark.line, "", "YAML syntax: " + e.msg);
  }
}

std::string read_file(const std::string& path) {
  std::ifstream in(path);
  if (!in) throw ConfigError(path + ": cannot open");
  std::ostringstream s;
  s << in.rdbuf();
  return s.str();
}

YAML::Node need(const Ctx& c, const YAML::Node& parent, const std::string& key, const std::string& field) {
  if (!parent.IsMap()) c.fail(parent, field, "expected a mapping");
  YAML::Node n = parent[key];
  if (!n) c.fail(parent, field, "missing");
  return n;
}

double number(const Ctx& c, const YAML::Node& n, const std::string& field) {
  if (!n.IsScalar()) c.fail(n, field, "expected a number");
  try {
    const double v = n.as<double>();
    if (!std::isfinite(v)) c.fail(n, field, "not a finite number");
    return v;
  } catch (const YAML::Exception&) {
    c.fail(n, field, "'" + n.Scalar() + "' is not a number");
  }
}

double number_or(const Ctx& c, const YAML::Node& parent, const std::string& key, const std::string& field,
                 double fallback) {
  if (!parent.IsMap() || !parent[key]) return fallback;
  return number(c, parent[key], field);
}

long integer(const Ctx& c, const YAML::Node& n, const std::string& field, long min, long max) {
  const double v = number(c, n, field);
  if (v != std::floor(v) || v < static_cast<double>(min) || v > static_cast<double>(max))
    c.fail(n, field, "must be an integer in " + std::to_string(min) + ".." + std::to_string(max));
  return static_cast<long>(v);
}

Vec2 point(const Ctx& c, const YAML::Node& n, const std::string& field) {
  if (!n.IsSequence() || n.size() != 2) c.fail(n, field, "expected [x, y]");
  return {number(c, n[0], field + "[0]"), number(c, n[1], field + "[1]")};
}

}  // namespace advee::robotsim::yaml
