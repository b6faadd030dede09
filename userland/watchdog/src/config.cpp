// SPDX-License-Identifier: GPL-2.0
#include "advee/watchdog/config.hpp"

#include <unistd.h>

#include <cerrno>
#include <cstring>
#include <filesystem>
#include <set>

namespace advee::watchdog {

using module::ConfigNode;

namespace {

void parse_backoff(const ConfigNode& n, BackoffConfig& b) {
  n.allow_only({"initial_s", "max_s", "factor", "stable_s"});
  b.initial = n.get_seconds("initial_s", b.initial, 0.01, 3600);
  b.max = n.get_seconds("max_s", b.max, 0.01, 86400);
  b.factor = n.get<double>("factor", b.factor);
  if (!(b.factor >= 1.0 && b.factor <= 10.0)) n.fail("factor", "must be between 1 and 10");
  b.stable = n.get_seconds("stable_s", b.stable, 0.1, 86400);
  if (b.max < b.initial) n.fail("max_s", "must not be below initial_s");
}

ModuleSpec parse_module(const ConfigNode& n, const std::filesystem::path& base) {
  n.allow_only({"name", "path", "args", "env", "start"});
  ModuleSpec m;
  m.name = n.get<std::string>("name");
  if (m.name.empty() || m.name == "*") n.fail("name", "must be a module name");
  std::filesystem::path p = n.get<std::string>("path");
  if (p.empty()) n.fail("path", "must not be empty");
  m.path = (p.is_absolute() ? p : base / p).lexically_normal().string();
  if (n.has("args")) {
    if (!n.yaml()["args"].IsSequence()) n.fail("args", "expected a list");
    m.args = n.get<std::vector<std::string>>("args");
  }
  if (n.has("env")) {
    if (!n.yaml()["env"].IsMap()) n.fail("env", "expected a mapping");
    m.env = n.get<std::map<std::string, std::string>>("env");
    for (const auto& [k, v] : m.env)
      if (k.empty() || k.find('=') != std::string::npos) n.fail("env", "bad variable name '" + k + "'");
  }
  m.start = n.get<bool>("start", true);
  return m;
}

}  // namespace

SupervisorConfig parse_supervisor_config(const ConfigNode& root) {
  root.allow_only({"module", "supervisor", "modules"});
  SupervisorConfig c;
  c.self.name = "watchdog";
  if (root.has("module")) module::parse_module_options(root.child("module"), c.self);
  if (root.has("supervisor")) {
    const auto s = root.child("supervisor");
    s.allow_only({"dead_after_s", "check_period_s", "term_grace_s", "startup_grace_s", "backoff"});
    c.dead_after = s.get_seconds("dead_after_s", c.dead_after, 0.1, 600);
    c.check_period = s.get_seconds("check_period_s", c.check_period, 0.01, 10);
    c.term_grace = s.get_seconds("term_grace_s", c.term_grace, 0.01, 600);
    c.startup_grace = s.get_seconds("startup_grace_s", c.startup_grace, 0.1, 600);
    if (c.check_period >= c.dead_after)
      s.fail("check_period_s", "must be shorter than dead_after_s");
    if (s.has("backoff")) parse_backoff(s.child("backoff"), c.backoff);
  }
  const auto mods = root.child("modules");
  if (!mods.yaml().IsSequence()) root.fail("modules", "expected a list of modules");
  const auto base = std::filesystem::path(root.file()).parent_path();
  std::set<std::string> names;
  for (const auto& item : mods.yaml()) {
    ConfigNode n(item, root.file());
    if (!item.IsMap()) mods.fail("modules", "each module is a mapping with name and path");
    auto m = parse_module(n, base);
    if (!names.insert(m.name).second) n.fail("name", "module '" + m.name + "' listed twice");
    if (m.name == c.self.name) n.fail("name", "the supervisor's own name");
    c.modules.push_back(std::move(m));
  }
  return c;
}

SupervisorConfig load_supervisor_config(const std::string& path) {
  return parse_supervisor_config(ConfigNode::load_file(path));
}

void check_module_programs(const SupervisorConfig& config) {
  std::string bad;
  for (const auto& m : config.modules) {
    std::error_code ec;
    std::string why;
    if (!std::filesystem::is_regular_file(m.path, ec))
      why = ec ? ec.message() : "not a regular file";
    else if (::access(m.path.c_str(), X_OK) != 0)
      why = std::strerror(errno);
    if (!why.empty()) bad += "\n  module " + m.name + ": path " + m.path + ": " + why;
  }
  if (!bad.empty()) throw module::ConfigError("modules that cannot be started:" + bad);
}

}  // namespace advee::watchdog
