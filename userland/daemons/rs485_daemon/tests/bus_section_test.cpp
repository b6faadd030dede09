// SPDX-License-Identifier: GPL-2.0
// The bus section both RS-485 daemons parse: one set of defaults, the
// kernel's ranges, errors naming file:line: key.
#include "advee/rs485_daemon/bus_section.hpp"

#include <gtest/gtest.h>

namespace advee::rs485_daemon {
namespace {

using namespace std::chrono_literals;

BusSection parse(const std::string& yaml, const std::string& default_device = "power") {
  return parse_bus_section(module::ConfigNode::parse(yaml, "test.yaml"), default_device);
}

std::string error_of(const std::string& yaml) {
  try {
    parse(yaml);
  } catch (const module::ConfigError& e) {
    return e.what();
  }
  return "no error";
}

TEST(BusSectionTest, DefaultsAreTheRobotsTimingAndTheKernelsBaudAndGap) {
  const BusSection s = parse("{}");
  EXPECT_EQ(s.device, "power");
  EXPECT_EQ(s.config.timeout, 20ms);
  EXPECT_EQ(s.config.retries, 1u);
  EXPECT_EQ(s.config.baud, rs485::BusConfig{}.baud);
  EXPECT_EQ(s.config.gap_chars, rs485::BusConfig{}.gap_chars);
}

TEST(BusSectionTest, EveryKeyIsRead) {
  const BusSection s = parse("{device: /dev/ttyTSU1, baud: 9600, timeout_ms: 2.5, retries: 3}");
  EXPECT_EQ(s.device, "/dev/ttyTSU1");
  EXPECT_EQ(s.config.baud, 9600u);
  EXPECT_EQ(s.config.timeout, 2500us);
  EXPECT_EQ(s.config.retries, 3u);
}

TEST(BusSectionTest, OutOfRangeAndUnknownKeysNameTheKey) {
  EXPECT_NE(error_of("{baud: 299}").find("baud"), std::string::npos);
  EXPECT_NE(error_of("{timeout_ms: 0.05}").find("timeout_ms: must be 0.1..10000"), std::string::npos);
  EXPECT_NE(error_of("{retries: 17}").find("retries: must be 0..16"), std::string::npos);
  EXPECT_NE(error_of("{device: ''}").find("device"), std::string::npos);
  try {
    parse_bus_section(module::ConfigNode::parse("{baud: 9600}", "test.yaml"), std::nullopt);
    ADD_FAILURE() << "a missing device without a default was accepted";
  } catch (const module::ConfigError& e) {
    EXPECT_NE(std::string(e.what()).find("device"), std::string::npos) << e.what();
  }
  const std::string unknown = error_of("{timeout: 20}");
  EXPECT_NE(unknown.find("test.yaml:1"), std::string::npos) << unknown;
  EXPECT_NE(unknown.find("timeout"), std::string::npos) << unknown;
}

}  // namespace
}  // namespace advee::rs485_daemon
