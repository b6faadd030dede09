// SPDX-License-Identifier: GPL-2.0
// driver_rs485 configuration: the installed examples parse to the robot's
// buses, and mistakes name their key.
#include <gtest/gtest.h>

#include <numbers>

#include "advee/driver_rs485/config.hpp"

using namespace advee;
using namespace advee::driver_rs485;

namespace {

Rs485Config parse(const std::string& body) {
  return parse_rs485_config(module::ConfigNode::parse("driver_rs485:\n" + body, "test.yaml"));
}

std::string error_of(const std::string& body) {
  try {
    parse(body);
  } catch (const module::ConfigError& e) {
    return e.what();
  }
  return "no error";
}

}  // namespace

TEST(Rs485Config, BusAExampleHasTwoSd1AndTheSo1) {
  const auto c = parse_rs485_config(module::ConfigNode::load_file(ADVEE_DRIVER_RS485_CONF "/driver_rs485a.yaml"));
  EXPECT_EQ(c.module.name, "driver_rs485a");
  EXPECT_EQ(c.bus.device, "a");
  EXPECT_EQ(c.bus.config.timeout, std::chrono::microseconds(20000));
  EXPECT_EQ(c.rate_hz, 4.0);
  ASSERT_EQ(c.sd1.size(), 2u);
  EXPECT_EQ(c.sd1[0].name, "front");
  EXPECT_EQ(c.sd1[0].address, 0x10);
  EXPECT_EQ(c.sd1[1].address, 0x11);
  ASSERT_EQ(c.sd1[1].srfs.size(), 8u);
  EXPECT_EQ(c.sd1[1].srfs[0].id, 8);
  EXPECT_NEAR(c.sd1[0].srfs[0].heading_rad, std::numbers::pi / 3, 1e-12);
  EXPECT_DOUBLE_EQ(c.sd1[0].srfs[0].x_m, 0.80);
  ASSERT_TRUE(c.so1);
  EXPECT_EQ(c.so1->address, 0x20);
  EXPECT_TRUE(c.so1->geometry.encoders_on_front);
  EXPECT_DOUBLE_EQ(c.so1->geometry.wheelbase_m, 0.62);
  EXPECT_FALSE(c.sbs1);
}

TEST(Rs485Config, BusBExampleHasTheSbs1) {
  const auto c = parse_rs485_config(module::ConfigNode::load_file(ADVEE_DRIVER_RS485_CONF "/driver_rs485b.yaml"));
  EXPECT_EQ(c.module.name, "driver_rs485b");
  EXPECT_EQ(c.rate_hz, 1.0);
  EXPECT_TRUE(c.sd1.empty());
  ASSERT_TRUE(c.sbs1);
  EXPECT_EQ(c.sbs1->address, 0x30);
  EXPECT_TRUE(c.sbs1->beacon_ids.empty());
  EXPECT_EQ(c.sbs1->resend_ids, std::chrono::milliseconds(10000));
}

TEST(Rs485Config, DefaultsAndBeaconIds) {
  const auto c = parse("  bus: {device: /dev/ttyTSU1}\n  sbs1: {address: 48, beacon_ids: [1, 2, 7]}\n");
  EXPECT_EQ(c.module.name, "driver_rs485");
  EXPECT_EQ(c.bus.config.baud, 115200u);
  EXPECT_EQ(c.bus.config.retries, 1u);
  EXPECT_EQ(c.sbs1->beacon_ids, (std::vector<std::uint8_t>{1, 2, 7}));
  const auto o = parse("  bus: {device: a}\n  so1: {address: 0x20}\n");
  EXPECT_EQ(o.so1->max_speed_mps, 1.5);
  // Slow enough for 8-bit counters at 4 Hz: 128 ticks are 0.078 m, 0.65 s at 0.12 m/s.
  const auto slow = parse("  bus: {device: a}\n  so1: {address: 0x20, width: 1, max_speed_mps: 0.12}\n");
  EXPECT_EQ(slow.so1->width, 1u);
}

TEST(Rs485Config, MistakesNameTheKey) {
  const std::string bus = "  bus: {device: a}\n";
  EXPECT_NE(error_of(bus + "  sd1: [{address: 0xff}]\n").find("address"), std::string::npos);
  EXPECT_NE(error_of(bus + "  so1: {address: 0x20, width: 3}\n").find("width"), std::string::npos);
  EXPECT_NE(error_of(bus + "  so1: {address: 0x20, track_m: 0}\n").find("track_m"), std::string::npos);
  EXPECT_NE(error_of(bus + "  so1: {address: 0x20, max_speed_mps: -1}\n").find("max_speed_mps"), std::string::npos);
  // 8-bit counters wrap within 0.05 s at 1.5 m/s (0.1 m wheels, 1024 ticks/rev):
  // every interval at 4 Hz would be ambiguous.
  EXPECT_NE(error_of(bus + "  so1: {address: 0x20, width: 1}\n").find("wrap ambiguously"), std::string::npos);
  EXPECT_NE(error_of(bus + "  so1: {address: 0x20, encoders: middle}\n").find("encoders"), std::string::npos);
  EXPECT_NE(error_of(bus + "  sd1: [{address: 16, srfs: [{index: 8, id: 1}]}]\n").find("index"),
            std::string::npos);
  EXPECT_NE(error_of(bus + "  sd1: [{address: 16, irs: [{index: 0, id: 1}, {index: 0, id: 2}]}]\n")
                .find("listed twice"),
            std::string::npos);
  EXPECT_NE(error_of(bus + "  sbs1: {address: 48, beacon_ids: [1, 300]}\n").find("beacon_ids"),
            std::string::npos);
  EXPECT_NE(error_of(bus + "  rate_hz: 0\n  so1: {address: 0x20}\n").find("rate_hz"), std::string::npos);
  EXPECT_NE(error_of(bus + "  sdl: []\n").find("sdl"), std::string::npos);
  EXPECT_NE(error_of(bus).find("no board"), std::string::npos);
  EXPECT_NE(error_of("  sd1: [{address: 16}]\n").find("bus"), std::string::npos);
  EXPECT_NE(error_of("  bus: {device: a, timeout_ms: 0}\n  so1: {address: 1}\n").find("timeout_ms"),
            std::string::npos);
  // file:line in the message.
  EXPECT_NE(error_of(bus + "  so1: {address: 0x20, width: 3}\n").find("test.yaml:"), std::string::npos);
}
