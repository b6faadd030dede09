// SPDX-License-Identifier: GPL-2.0
#include "advee/module/config.hpp"

#include <algorithm>
#include <cstdint>
#include <map>
#include <vector>

namespace advee::module {

ConfigNode ConfigNode::load_file(const std::string& path) {
  try {
    YAML::Node n = YAML::LoadFile(path);
    if (!n.IsMap()) throw ConfigError(path + ": expected a mapping at the top level");
    return ConfigNode(n, path);
  } catch (const YAML::BadFile&) {
    throw ConfigError(path + ": cannot open the configuration file");
  } catch (const YAML::Exception& e) {
    throw ConfigError(path + ":" + std::to_string(e.mark.line + 1) + ": " + e.msg);
  }
}

ConfigNode ConfigNode::parse(const std::string& text, std::string name) {
  try {
    YAML::Node n = YAML::Load(text);
    if (!n.IsMap()) throw ConfigError(name + ": expected a mapping at the top level");
    return ConfigNode(n, std::move(name));
  } catch (const YAML::Exception& e) {
    throw ConfigError(name + ":" + std::to_string(e.mark.line + 1) + ": " + e.msg);
  }
}

bool ConfigNode::has(std::string_view key) const {
  return node_.IsMap() && node_[std::string(key)].IsDefined() && !node_[std::string(key)].IsNull();
}

void ConfigNode::fail(std::string_view key, const std::string& msg) const {
  YAML::Mark m = node_.Mark();
  if (node_.IsMap() && node_[std::string(key)].IsDefined()) m = node_[std::string(key)].Mark();
  throw_config_error(file_, m.line, key, msg);
}

ConfigNode ConfigNode::child(std::string_view key) const {
  if (!has(key)) fail(key, "missing");
  return ConfigNode(node_[std::string(key)], file_);
}

void ConfigNode::allow_only(std::initializer_list<std::string_view> allowed) const {
  if (!node_.IsMap()) fail("", "expected a mapping");
  for (const auto& kv : node_) {
    const auto k = kv.first.as<std::string>();
    if (std::find(allowed.begin(), allowed.end(), k) == allowed.end())
      fail(k, "unknown key");
  }
}

template <typename T>
T ConfigNode::get(std::string_view key) const {
  if (!has(key)) fail(key, "missing");
  const YAML::Node v = node_[std::string(key)];
  try {
    if constexpr (std::is_same_v<T, std::string>) {
      if (!v.IsScalar()) fail(key, "expected a string");
    }
    return v.as<T>();
  } catch (const YAML::Exception&) {
    if constexpr (std::is_same_v<T, bool>) fail(key, "expected true or false");
    else if constexpr (std::is_integral_v<T>) fail(key, "expected an integer");
    else if constexpr (std::is_floating_point_v<T>) fail(key, "expected a number");
    else fail(key, "wrong type");
  }
}

template std::string ConfigNode::get<std::string>(std::string_view) const;
template bool ConfigNode::get<bool>(std::string_view) const;
template int ConfigNode::get<int>(std::string_view) const;
template unsigned ConfigNode::get<unsigned>(std::string_view) const;
template double ConfigNode::get<double>(std::string_view) const;
template std::vector<std::string> ConfigNode::get<std::vector<std::string>>(std::string_view) const;
template std::map<std::string, std::string> ConfigNode::get<std::map<std::string, std::string>>(
    std::string_view) const;

std::chrono::milliseconds ConfigNode::get_seconds(std::string_view key,
                                                  std::chrono::milliseconds fallback, double min_s,
                                                  double max_s) const {
  if (!has(key)) return fallback;
  const double s = get<double>(key);
  if (!(s >= min_s && s <= max_s))
    fail(key, "must be between " + std::to_string(min_s) + " and " + std::to_string(max_s) +
                  " seconds");
  return std::chrono::milliseconds(static_cast<std::int64_t>(s * 1000 + 0.5));
}

namespace {

std::int8_t severity_threshold(const ConfigNode& n, std::string_view key, std::int8_t fallback) {
  if (!n.has(key)) return fallback;
  const auto s = n.get<std::string>(key);
  if (s == "none") return kSeverityNone;
  const auto v = parse_severity(s);
  if (!v) n.fail(key, "expected notice, warning, error or none, got '" + s + "'");
  return static_cast<std::int8_t>(*v);
}

}  // namespace

void parse_module_options(const ConfigNode& n, ModuleOptions& o) {
  n.allow_only({"name", "lcm_url", "log_root", "print_severity", "send_severity", "error_channel",
                "announce_period_s", "start_state"});
  o.name = n.get<std::string>("name", o.name);
  if (o.name.empty()) n.fail("name", "must not be empty");
  o.lcm_url = n.get<std::string>("lcm_url", o.lcm_url);
  o.log_root = n.get<std::string>("log_root", o.log_root);
  o.errors.print_severity = severity_threshold(n, "print_severity", o.errors.print_severity);
  o.errors.send_severity = severity_threshold(n, "send_severity", o.errors.send_severity);
  o.errors.channel = n.get<std::string>("error_channel", o.errors.channel);
  // Faster than 1 s is allowed; slower would let the supervisor's 2 s
  // deadline kill a healthy module.
  o.announce_period = n.get_seconds("announce_period_s", o.announce_period, 0.01, 1.0);
  if (n.has("start_state")) {
    const auto s = parse_state(n.get<std::string>("start_state"));
    if (!s || (*s != State::Run && *s != State::Pause))
      n.fail("start_state", "expected run or pause");
    o.start_state = *s;
  }
}

}  // namespace advee::module
