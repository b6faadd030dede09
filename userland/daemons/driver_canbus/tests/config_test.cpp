// SPDX-License-Identifier: GPL-2.0
// driver_canbus configuration: the robot's file, defaults, mistakes.
#include <gtest/gtest.h>

#include <numbers>

#include "advee/driver_canbus/config.hpp"

namespace advee::driver_canbus {
namespace {

using module::ConfigError;
using module::ConfigNode;

CanbusConfig parse(const std::string& yaml) { return parse_canbus_config(ConfigNode::parse(yaml, "test.yaml")); }

TEST(CanbusConfigTest, TheRobotsFileHasTheRobotsUnits) {
  const auto c = parse_canbus_config(ConfigNode::load_file(ADVEE_DRIVER_CANBUS_CONF "/driver_canbus.yaml"));
  EXPECT_EQ(c.module.name, "driver_canbus");
  EXPECT_EQ(c.interface, "can0");
  EXPECT_EQ(c.controller.epos.node, 1);
  EXPECT_EQ(c.controller.icla.node, 2);
  EXPECT_DOUBLE_EQ(c.controller.epos.wheel_radius_m, 0.125);
  EXPECT_DOUBLE_EQ(c.controller.epos.gear_ratio, 26);
  EXPECT_DOUBLE_EQ(c.controller.icla.units_per_rad, 10000);
  EXPECT_NEAR(c.controller.steering_limit_rad, 30 * std::numbers::pi / 180, 1e-12);
  EXPECT_EQ(c.controller.command_timeout, std::chrono::milliseconds(1000));
  EXPECT_DOUBLE_EQ(c.publish_hz, 4);
  EXPECT_FALSE(c.controller.home_on_start);
  EXPECT_EQ(c.master_heartbeat, std::chrono::milliseconds(100));
}

TEST(CanbusConfigTest, AnEmptyFileGivesTheSameDefaults) {
  const auto c = parse("{}");
  EXPECT_EQ(c.interface, "can0");
  EXPECT_DOUBLE_EQ(c.controller.epos.wheel_radius_m, 0.125);
  EXPECT_DOUBLE_EQ(c.controller.icla.units_per_rad, 10000);
  EXPECT_EQ(c.controller.command_timeout, std::chrono::milliseconds(1000));
}

TEST(CanbusConfigTest, KeysAreRead) {
  const auto c = parse(
      "driver_canbus:\n"
      "  interface: vcan0\n"
      "  command_timeout_s: 0.5\n"
      "  home_on_start: true\n"
      "  propulsion: {node: 5, wheel_radius_m: 0.1, max_speed_mps: 1}\n"
      "  steering: {node: 6, limit_deg: 20, homing: {method: 35, timeout_s: 5}}\n");
  EXPECT_EQ(c.interface, "vcan0");
  EXPECT_EQ(c.controller.command_timeout, std::chrono::milliseconds(500));
  EXPECT_TRUE(c.controller.home_on_start);
  EXPECT_EQ(c.controller.epos.node, 5);
  EXPECT_DOUBLE_EQ(c.controller.max_speed_mps, 1);
  EXPECT_EQ(c.controller.icla.node, 6);
  EXPECT_EQ(c.controller.icla.homing_method, 35);
  EXPECT_EQ(c.controller.icla.drive.homing_timeout, std::chrono::milliseconds(5000));
  EXPECT_NEAR(c.controller.steering_limit_rad, 20 * std::numbers::pi / 180, 1e-12);
}

TEST(CanbusConfigTest, MistakesNameTheKey) {
  auto fails_on = [](const std::string& yaml, const std::string& key) {
    try {
      parse(yaml);
    } catch (const ConfigError& e) {
      EXPECT_NE(std::string(e.what()).find(key), std::string::npos) << e.what();
      EXPECT_NE(std::string(e.what()).find("test.yaml"), std::string::npos) << e.what();
      return;
    }
    ADD_FAILURE() << "accepted: " << yaml;
  };
  fails_on("driver_canbus: {interfce: can0}", "interfce");
  fails_on("driver_canbus: {propulsion: {node: 0}}", "node");
  fails_on("driver_canbus: {propulsion: {node: 128}}", "node");
  fails_on("driver_canbus: {steering: {node: 1}}", "steering");
  fails_on("driver_canbus: {command_timeout_s: 0}", "command_timeout_s");
  fails_on("driver_canbus: {steering: {limit_deg: 120}}", "limit_deg");
  fails_on("driver_canbus: {propulsion: {wheel_radius_m: -1}}", "wheel_radius_m");
  fails_on("driver_canbus: {publish_hz: 0}", "publish_hz");
  fails_on("driver_canbus: {master: {node_id: 1}}", "master");
}

TEST(CanbusConfigTest, DcfGivesTheIdentityToCheckAndTheConfiguration) {
  const auto c = parse("driver_canbus:\n"
                       "  propulsion: {node: 3, dcf: " ADVEE_CANOPEN_DATA "/epos-70-10.eds}\n");
  ASSERT_TRUE(c.controller.epos.drive.device);
  EXPECT_EQ(c.controller.epos.drive.device->node, 3);
  EXPECT_EQ(c.controller.epos.drive.device->identity[0], 0x000000FBu);
  EXPECT_EQ(c.controller.epos.drive.device->identity[1], 0x64200000u);
  EXPECT_FALSE(c.controller.epos.drive.device->identity[3]);  // no serial in an EDS
  EXPECT_FALSE(c.controller.icla.drive.device);
}

TEST(CanbusConfigTest, AnUnusableDcfNamesTheKeyAndTheFileLine) {
  try {
    parse("driver_canbus:\n  steering: {dcf: /nonexistent/icla.dcf}\n");
    ADD_FAILURE() << "accepted";
  } catch (const ConfigError& e) {
    EXPECT_NE(std::string(e.what()).find("dcf"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("/nonexistent/icla.dcf: expected a readable file"), std::string::npos)
        << e.what();
  }
}

}  // namespace
}  // namespace advee::driver_canbus
