// SPDX-License-Identifier: GPL-2.0
#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>

#include "advee/watchdog/config.hpp"

using namespace advee::watchdog;
using advee::module::ConfigError;
using advee::module::ConfigNode;
using namespace std::chrono_literals;

namespace {

std::string error_of(const std::string& yaml) {
  try {
    parse_supervisor_config(ConfigNode::parse(yaml, "/etc/advee/watchdog.yaml"));
  } catch (const ConfigError& e) {
    return e.what();
  }
  return "";
}

TEST(SupervisorConfig, FullFile) {
  const auto c = parse_supervisor_config(ConfigNode::parse(
      "module:\n"
      "  name: wd\n"
      "supervisor:\n"
      "  dead_after_s: 1.5\n"
      "  check_period_s: 0.1\n"
      "  term_grace_s: 0.5\n"
      "  backoff: {initial_s: 0.25, max_s: 8, factor: 3, stable_s: 4}\n"
      "modules:\n"
      "  - name: driver_aux\n"
      "    path: /usr/libexec/advee/driver_aux\n"
      "    args: [--config, /etc/advee/driver_aux.yaml]\n"
      "    env: {ADVEE_X: '1'}\n"
      "  - name: driver_power\n"
      "    path: bin/driver_power\n"
      "    start: false\n",
      "/opt/advee/conf/watchdog.yaml"));
  EXPECT_EQ(c.self.name, "wd");
  EXPECT_EQ(c.dead_after, 1500ms);
  EXPECT_EQ(c.check_period, 100ms);
  EXPECT_EQ(c.term_grace, 500ms);
  EXPECT_EQ(c.startup_grace, 5000ms);
  EXPECT_EQ(c.backoff.initial, 250ms);
  EXPECT_EQ(c.backoff.max, 8000ms);
  EXPECT_EQ(c.backoff.factor, 3.0);
  EXPECT_EQ(c.backoff.stable, 4000ms);
  ASSERT_EQ(c.modules.size(), 2u);
  EXPECT_EQ(c.modules[0].args, (std::vector<std::string>{"--config", "/etc/advee/driver_aux.yaml"}));
  EXPECT_EQ(c.modules[0].env.at("ADVEE_X"), "1");
  EXPECT_TRUE(c.modules[0].start);
  // Relative paths are relative to the configuration file (thesis: bin/...).
  EXPECT_EQ(c.modules[1].path, "/opt/advee/conf/bin/driver_power");
  EXPECT_FALSE(c.modules[1].start);
}

TEST(SupervisorConfig, DefaultsAreTheThesisTimings) {
  const auto c = parse_supervisor_config(ConfigNode::parse("modules: []\n"));
  EXPECT_EQ(c.self.name, "watchdog");
  EXPECT_EQ(c.dead_after, 2000ms);
  EXPECT_EQ(c.check_period, 200ms);
  EXPECT_TRUE(c.modules.empty());
}

TEST(SupervisorConfig, Errors) {
  EXPECT_EQ(error_of("modules:\n  - name: a\n"), "/etc/advee/watchdog.yaml:2: path: missing");
  EXPECT_EQ(error_of("modules:\n  - {name: a, path: /a}\n  - {name: a, path: /b}\n"),
            "/etc/advee/watchdog.yaml:3: name: module 'a' listed twice");
  EXPECT_EQ(error_of("modules:\n  - {name: a, path: /a, restart: always}\n"),
            "/etc/advee/watchdog.yaml:2: restart: unknown key");
  EXPECT_EQ(error_of("modules:\n  - {name: a, path: /a, args: --verbose}\n"),
            "/etc/advee/watchdog.yaml:2: args: expected a list");
  EXPECT_EQ(error_of("modules:\n  - {name: watchdog, path: /a}\n"),
            "/etc/advee/watchdog.yaml:2: name: the supervisor's own name");
  EXPECT_EQ(error_of("supervisor:\n  dead_after_s: 0.1\n  check_period_s: 0.2\nmodules: []\n"),
            "/etc/advee/watchdog.yaml:3: check_period_s: must be shorter than dead_after_s");
  EXPECT_EQ(error_of("supervisor:\n  backoff: {initial_s: 5, max_s: 1}\nmodules: []\n"),
            "/etc/advee/watchdog.yaml:2: max_s: must not be below initial_s");
  EXPECT_EQ(error_of("modules: {a: 1}\n"), "/etc/advee/watchdog.yaml:1: modules: expected a list of modules");
  EXPECT_EQ(error_of("module: {}\n"), "/etc/advee/watchdog.yaml:1: modules: missing");
}

// A module whose program cannot be executed is a configuration error (the
// supervisor would restart it forever on exit code 127), named with its path.
TEST(SupervisorConfig, ModuleProgramsMustBeExecutable) {
  const auto data = std::filesystem::temp_directory_path() /
                    ("advee-config-test-" + std::to_string(::getpid()));
  std::ofstream(data) << "not a program\n";
  std::filesystem::permissions(data, std::filesystem::perms::owner_read);
  auto c = parse_supervisor_config(ConfigNode::parse(
      "modules:\n"
      "  - {name: shell, path: /bin/sh}\n"
      "  - {name: gone, path: /nonexistent/driver}\n"
      "  - {name: dir, path: /}\n"
      "  - {name: data, path: " + data.string() + "}\n",
      "/etc/advee/watchdog.yaml"));
  std::string what;
  try {
    check_module_programs(c);
  } catch (const ConfigError& e) {
    what = e.what();
  }
  std::filesystem::remove(data);
  EXPECT_EQ(what, "modules that cannot be started:\n"
                  "  module gone: path /nonexistent/driver: No such file or directory\n"
                  "  module dir: path /: not a regular file\n"
                  "  module data: path " + data.string() + ": Permission denied");
  c.modules.resize(1);
  EXPECT_NO_THROW(check_module_programs(c));
}

}  // namespace
