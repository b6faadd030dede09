// SPDX-License-Identifier: GPL-2.0
// YAML configuration files (yaml-cpp). Errors name the file, the line and the
// key; unknown keys are errors too (a typo must not silently fall back to a
// default on the robot).
#pragma once

#include <yaml-cpp/yaml.h>

#include <chrono>
#include <initializer_list>
#include <stdexcept>
#include <string>
#include <string_view>

#include "advee/config_error.hpp"
#include "advee/module/error.hpp"
#include "advee/module/state.hpp"

namespace advee::module {

using advee::ConfigError;  // advee/config_error.hpp: one type for every configuration file

// A node together with the file it came from, for error messages.
class ConfigNode {
 public:
  ConfigNode(YAML::Node node, std::string file) : node_(std::move(node)), file_(std::move(file)) {}

  static ConfigNode load_file(const std::string& path);           // throws ConfigError
  static ConfigNode parse(const std::string& text, std::string name = "<string>");

  const YAML::Node& yaml() const { return node_; }
  bool has(std::string_view key) const;
  ConfigNode child(std::string_view key) const;  // required map/sequence
  // Fails for keys outside `allowed`.
  void allow_only(std::initializer_list<std::string_view> allowed) const;

  template <typename T>
  T get(std::string_view key) const;  // required scalar
  template <typename T>
  T get(std::string_view key, T fallback) const {
    return has(key) ? get<T>(key) : fallback;
  }
  std::chrono::milliseconds get_seconds(std::string_view key, std::chrono::milliseconds fallback,
                                        double min_s, double max_s) const;

  [[noreturn]] void fail(std::string_view key, const std::string& msg) const;
  const std::string& file() const { return file_; }

 private:
  YAML::Node node_;
  std::string file_;
};

// The `module:` section every module's configuration file may have.
struct ModuleOptions {
  std::string name;
  std::string lcm_url;   // empty: advee/msgs/bus.hpp decides (LCM_DEFAULT_URL, /etc/advee/lcm.conf, LCM's default)
  std::string log_root;  // empty: no log directory unless ADVEE_LOG_DIR is set
  ErrorReporter::Config errors;
  std::chrono::milliseconds announce_period{1000};
  State start_state = State::Run;  // after INIT: RUN or PAUSE
  std::vector<int> extra_signals;  // blocked and delivered to Module::on_signal (not from YAML)
};

// Fills `opts` from `section` (keys name, lcm_url, log_root, print_severity,
// send_severity, error_channel, announce_period_s, start_state).
void parse_module_options(const ConfigNode& section, ModuleOptions& opts);

}  // namespace advee::module
