// SPDX-License-Identifier: GPL-2.0
// The module: section and the errors a wrong file produces (file:line: key).
#include <gtest/gtest.h>

#include "advee/module/config.hpp"

using namespace advee::module;

namespace {

std::string error_of(const std::string& yaml) {
  try {
    auto root = ConfigNode::parse(yaml, "test.yaml");
    ModuleOptions o;
    o.name = "fallback";
    parse_module_options(root.child("module"), o);
  } catch (const ConfigError& e) {
    return e.what();
  }
  return "";
}

TEST(Config, ModuleSectionIsRead) {
  auto root = ConfigNode::parse(
      "module:\n"
      "  name: driver_aux\n"
      "  lcm_url: memq://\n"
      "  log_root: /tmp/x\n"
      "  print_severity: notice\n"
      "  send_severity: none\n"
      "  error_channel: ERRS\n"
      "  announce_period_s: 0.5\n"
      "  start_state: pause\n");
  ModuleOptions o;
  parse_module_options(root.child("module"), o);
  EXPECT_EQ(o.name, "driver_aux");
  EXPECT_EQ(o.lcm_url, "memq://");
  EXPECT_EQ(o.log_root, "/tmp/x");
  EXPECT_EQ(o.errors.print_severity, static_cast<std::int8_t>(Severity::Notice));
  EXPECT_EQ(o.errors.send_severity, kSeverityNone);
  EXPECT_EQ(o.errors.channel, "ERRS");
  EXPECT_EQ(o.announce_period, std::chrono::milliseconds(500));
  EXPECT_EQ(o.start_state, State::Pause);
}

TEST(Config, DefaultsStayWhenKeysAreAbsent) {
  auto root = ConfigNode::parse("module: {}\n");
  ModuleOptions o;
  o.name = "driver_aux";
  parse_module_options(root.child("module"), o);
  EXPECT_EQ(o.name, "driver_aux");
  EXPECT_EQ(o.announce_period, std::chrono::milliseconds(1000));
  EXPECT_EQ(o.start_state, State::Run);
  EXPECT_EQ(o.errors.channel, "CM_DATA_ERROR");
}

TEST(Config, ErrorsNameFileLineAndKey) {
  EXPECT_EQ(error_of("module:\n  name: a\n  print_severty: notice\n"),
            "test.yaml:3: print_severty: unknown key");
  EXPECT_EQ(error_of("module:\n  send_severity: loud\n"),
            "test.yaml:2: send_severity: expected notice, warning, error or none, got 'loud'");
  EXPECT_EQ(error_of("module:\n  announce_period_s: 2\n"),
            "test.yaml:2: announce_period_s: must be between 0.010000 and 1.000000 seconds");
  EXPECT_EQ(error_of("module:\n  announce_period_s: soon\n"),
            "test.yaml:2: announce_period_s: expected a number");
  EXPECT_EQ(error_of("module:\n  start_state: stop\n"), "test.yaml:2: start_state: expected run or pause");
  EXPECT_EQ(error_of("module:\n  name: [a, b]\n"), "test.yaml:2: name: expected a string");
  EXPECT_EQ(error_of("other: 1\n"), "test.yaml:1: module: missing");
}

TEST(Config, MalformedYamlAndMissingFile) {
  const auto e = error_of("module:\n  name: [unclosed\n");
  EXPECT_EQ(e.rfind("test.yaml:", 0), 0u) << e;
  EXPECT_THROW(ConfigNode::load_file("/nonexistent/advee.yaml"), ConfigError);
  try {
    ConfigNode::load_file("/nonexistent/advee.yaml");
  } catch (const ConfigError& err) {
    EXPECT_STREQ(err.what(), "/nonexistent/advee.yaml: cannot open the configuration file");
  }
  EXPECT_THROW(ConfigNode::parse("- a\n- b\n"), ConfigError);  // not a mapping
}

}  // namespace
