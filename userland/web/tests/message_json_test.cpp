// SPDX-License-Identifier: GPL-2.0
// Every channel's message type -> the JSON the page reads.
#include "advee/web/message_json.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>

#include "advee/msgs/channels.hpp"
#include "common/cmd_state_t.hpp"
#include "common/data_module_phase_t.hpp"
#include "common/data_state_t.hpp"
#include "common/error_t.hpp"
#include "lowlevel/cmd_homing_t.hpp"
#include "lowlevel/cmd_motion_t.hpp"
#include "lowlevel/cmd_power_t.hpp"
#include "lowlevel/data_active_beacons_t.hpp"
#include "lowlevel/data_beacons_t.hpp"
#include "lowlevel/data_drives_t.hpp"
#include "lowlevel/data_fans_t.hpp"
#include "lowlevel/data_odo_t.hpp"
#include "lowlevel/data_power_t.hpp"
#include "lowlevel/data_srfs_t.hpp"
#include "lowlevel/data_temperature_t.hpp"
#include "lowlevel/event_stop_t.hpp"
#if __has_include("sim/data_pose_t.hpp")
#include "sim/data_pose_t.hpp"
#define ADVEE_WEB_HAVE_SIM_POSE 1
#endif

namespace advee::web {
namespace {

using nlohmann::json;
namespace msgs = advee::msgs;

template <typename T>
std::vector<std::uint8_t> encode(const T& m) {
  std::vector<std::uint8_t> buf(static_cast<std::size_t>(m.getEncodedSize()));
  EXPECT_EQ(m.encode(buf.data(), 0, static_cast<int>(buf.size())), static_cast<int>(buf.size()));
  return buf;
}

template <typename T>
json convert(std::string_view channel, const T& m) {
  const auto buf = encode(m);
  auto j = message_to_json(channel, buf.data(), buf.size());
  EXPECT_TRUE(j.has_value()) << channel;
  return j.value_or(json());
}

TEST(MessageJson, DataState) {
  common::data_state_t m{};
  m.utime = 1700000000123456;
  m.module = "driver_aux";
  m.state = common::data_state_t::RUN;
  m.pid = 4242;
  const json j = convert(msgs::kDataState.name, m);
  EXPECT_EQ(j, (json{{"channel", "CM_DATA_STATE"}, {"utime", 1700000000123456}, {"module", "driver_aux"},
                     {"state", 3}, {"pid", 4242}}));
}

TEST(MessageJson, CmdState) {
  common::cmd_state_t m{};
  m.utime = 5;
  m.module = "diagnostic_center";
  m.target = "*";
  m.state = common::data_state_t::STOP;
  m.manual = 1;
  const json j = convert(msgs::kCmdState.name, m);
  EXPECT_EQ(j["target"], "*");
  EXPECT_EQ(j["state"], 2);
  EXPECT_EQ(j["manual"], true);
}

TEST(MessageJson, Error) {
  common::error_t m{};
  m.utime = 7;
  m.module = "driver_rs485a";
  m.number = 110;
  m.text = "no \"answer\"";
  m.fatal = 0;
  m.type = common::error_t::TYPE_TIMEOUT;
  m.severity = common::error_t::SEVERITY_ERROR;
  m.file = "bus.cpp";
  m.line = 99;
  const json j = convert(msgs::kDataError.name, m);
  EXPECT_EQ(j["text"], "no \"answer\"");
  EXPECT_EQ(j["fatal"], false);
  EXPECT_EQ(j["type"], 1);
  EXPECT_EQ(j["severity"], 2);
  EXPECT_EQ(j["number"], 110);
  EXPECT_EQ(j["line"], 99);
  // The quote survives the trip through JSON text.
  EXPECT_EQ(json::parse(j.dump())["text"], "no \"answer\"");
}

TEST(MessageJson, ModulePhase) {
  common::data_module_phase_t m{};
  m.utime = 1;
  m.module = "advee-watchdog";
  m.target = "driver_power";
  m.phase = common::data_module_phase_t::TERMINATED;
  m.pid = 0;
  m.restarts = 3;
  m.exit_status = 137;
  m.next_start_ms = 2000;
  m.command = common::data_state_t::RUN;
  const json j = convert(msgs::kDataModules.name, m);
  EXPECT_EQ(j["target"], "driver_power");
  EXPECT_EQ(j["phase"], 4);
  EXPECT_EQ(j["restarts"], 3);
  EXPECT_EQ(j["exit_status"], 137);
  EXPECT_EQ(j["next_start_ms"], 2000);
  EXPECT_EQ(j["command"], 3);
}

TEST(MessageJson, SrfsKeepOrderAndNoEcho) {
  lowlevel::data_srfs_t m{};
  m.utime = 2;
  m.module = "driver_rs485a";
  m.num_srfs = 3;
  m.srf_id = {0, 7, 15};
  m.srf_range_m = {1.5f, -1.0f, std::numeric_limits<float>::quiet_NaN()};
  m.num_irs = 1;
  m.ir_id = {2};
  m.ir_range_m = {0.125f};
  const json j = convert(msgs::kDataSrfs.name, m);
  EXPECT_EQ(j["srf_id"], (json{0, 7, 15}));
  EXPECT_DOUBLE_EQ(j["srf_range_m"][0].get<double>(), 1.5);
  EXPECT_DOUBLE_EQ(j["srf_range_m"][1].get<double>(), -1.0);  // no echo: as sent
  EXPECT_TRUE(j["srf_range_m"][2].is_null());                 // NaN: JSON null
  EXPECT_EQ(j["ir_id"], (json{2}));
  EXPECT_DOUBLE_EQ(j["ir_range_m"][0].get<double>(), 0.125);
  EXPECT_NO_THROW(json::parse(j.dump()));
}

TEST(MessageJson, Odometry) {
  lowlevel::data_odo_t m{};
  m.utime = 3;
  m.module = "driver_rs485a";
  m.ticks_left = 120;
  m.ticks_right = -4;
  m.interval_s = 0.25;
  m.speed_mps = 0.5;
  m.yaw_rate_radps = -0.1;
  const json j = convert(msgs::kDataOdo.name, m);
  EXPECT_EQ(j["ticks_left"], 120);
  EXPECT_EQ(j["ticks_right"], -4);
  EXPECT_DOUBLE_EQ(j["interval_s"].get<double>(), 0.25);
  EXPECT_DOUBLE_EQ(j["speed_mps"].get<double>(), 0.5);
  EXPECT_DOUBLE_EQ(j["yaw_rate_radps"].get<double>(), -0.1);
}

TEST(MessageJson, Beacons) {
  lowlevel::data_beacons_t m{};
  m.utime = 4;
  m.module = "driver_rs485b";
  m.count = 2;
  m.id = {1, 4};
  m.bearing_rad = {0.5f, -2.0f};
  const json j = convert(msgs::kDataBeacons.name, m);
  EXPECT_EQ(j["id"], (json{1, 4}));
  EXPECT_DOUBLE_EQ(j["bearing_rad"][1].get<double>(), -2.0);
}

TEST(MessageJson, ActiveBeacons) {
  lowlevel::data_active_beacons_t m{};
  m.utime = 4;
  m.module = "planner";
  m.count = 3;
  m.id = {1, 2, 9};
  EXPECT_EQ(convert(msgs::kDataActiveBeacons.name, m)["id"], (json{1, 2, 9}));
}

TEST(MessageJson, Commands) {
  lowlevel::cmd_motion_t mo{};
  mo.utime = 1;
  mo.module = "diagnostic_center";
  mo.speed_mps = -0.3;
  mo.steering_rad = 0.2;
  const json jm = convert(msgs::kCmdMotion.name, mo);
  EXPECT_DOUBLE_EQ(jm["speed_mps"].get<double>(), -0.3);
  EXPECT_DOUBLE_EQ(jm["steering_rad"].get<double>(), 0.2);

  lowlevel::cmd_homing_t h{};
  h.utime = 1;
  h.module = "diagnostic_center";
  h.axis = lowlevel::cmd_homing_t::AXIS_STEERING;
  EXPECT_EQ(convert(msgs::kCmdHoming.name, h)["axis"], 0);

  lowlevel::cmd_power_t p{};
  p.utime = 1;
  p.module = "diagnostic_center";
  p.action = lowlevel::cmd_power_t::ACTION_SET_OUTPUT;
  p.output = 3;
  p.on = 1;
  const json jp = convert(msgs::kCmdPower.name, p);
  EXPECT_EQ(jp["action"], 0);
  EXPECT_EQ(jp["output"], 3);
  EXPECT_EQ(jp["on"], true);
}

TEST(MessageJson, PowerBooleansAreBooleans) {
  lowlevel::data_power_t m{};
  m.utime = 1;
  m.module = "driver_power";
  m.battery_v = 24.5f;
  m.num_outputs = 3;
  m.on = {1, 0, 1};
  m.current_a = {1.5f, 0.0f, -1.0f};
  m.paused = 1;
  const json j = convert(msgs::kDataPower.name, m);
  EXPECT_DOUBLE_EQ(j["battery_v"].get<double>(), 24.5);
  EXPECT_EQ(j["on"], (json{true, false, true}));
  EXPECT_DOUBLE_EQ(j["current_a"][2].get<double>(), -1.0);
  EXPECT_EQ(j["paused"], true);
}

TEST(MessageJson, EventStop) {
  lowlevel::event_stop_t m{};
  m.utime = 1;
  m.module = "driver_power";
  m.stop = 1;
  m.source = lowlevel::event_stop_t::SOURCE_DIO;
  const json j = convert(msgs::kEventStop.name, m);
  EXPECT_EQ(j["stop"], true);
  EXPECT_EQ(j["source"], 1);
}

TEST(MessageJson, TemperaturesAndFans) {
  lowlevel::data_temperature_t t{};
  t.utime = 1;
  t.module = "driver_aux";
  t.count = 2;
  t.label = {"temp1", "temp2"};
  t.celsius = {41.5f, 33.25f};
  const json jt = convert(msgs::kDataTemperature.name, t);
  EXPECT_EQ(jt["label"], (json{"temp1", "temp2"}));
  EXPECT_DOUBLE_EQ(jt["celsius"][0].get<double>(), 41.5);
  EXPECT_DOUBLE_EQ(jt["celsius"][1].get<double>(), 33.25);

  lowlevel::data_fans_t f{};
  f.utime = 1;
  f.module = "driver_aux";
  f.count = 2;
  f.label = {"fan1", "fan2"};
  f.rpm = {2400, -1};
  f.fault = {0, 1};
  f.fan_fail = 1;
  f.pwm = {128, -1};
  const json jf = convert(msgs::kDataFans.name, f);
  EXPECT_EQ(jf["rpm"], (json{2400, -1}));
  EXPECT_EQ(jf["fault"], (json{false, true}));
  EXPECT_EQ(jf["fan_fail"], true);
  EXPECT_EQ(jf["pwm"], (json{128, -1}));
}

TEST(MessageJson, Drives) {
  lowlevel::data_drives_t m{};
  m.utime = 1;
  m.module = "driver_canbus";
  m.num_drives = 2;
  m.axis = {lowlevel::data_drives_t::AXIS_PROPULSION, lowlevel::data_drives_t::AXIS_STEERING};
  m.node = {1, 2};
  m.state = {"operation enabled", "fault"};
  m.fault = {0, 1};
  m.error_code = {0, 0x8611};
  m.homed = {0, 1};
  m.speed_mps = 0.45;
  m.steering_rad = 0.1;
  m.cmd_speed_mps = 0.5;
  m.cmd_steering_rad = 0.12;
  m.stopped = 1;
  m.stop_reason = "fault";
  const json j = convert(msgs::kDataDrives.name, m);
  EXPECT_EQ(j["axis"], (json{0, 1}));
  EXPECT_EQ(j["node"], (json{1, 2}));
  EXPECT_EQ(j["state"], (json{"operation enabled", "fault"}));
  EXPECT_EQ(j["fault"], (json{false, true}));
  EXPECT_EQ(j["error_code"], (json{0, 0x8611}));
  EXPECT_EQ(j["homed"], (json{false, true}));
  EXPECT_DOUBLE_EQ(j["speed_mps"].get<double>(), 0.45);
  EXPECT_DOUBLE_EQ(j["cmd_speed_mps"].get<double>(), 0.5);
  EXPECT_DOUBLE_EQ(j["steering_rad"].get<double>(), 0.1);
  EXPECT_DOUBLE_EQ(j["cmd_steering_rad"].get<double>(), 0.12);
  EXPECT_EQ(j["stopped"], true);
  EXPECT_EQ(j["stop_reason"], "fault");
}

#ifdef ADVEE_WEB_HAVE_SIM_POSE
TEST(MessageJson, SimulatorGroundTruth) {
  sim::data_pose_t m{};
  m.utime = 9;
  m.sim_time_s = 12.5;
  m.x_m = 2.5;
  m.y_m = -1.25;
  m.heading_rad = 1.5;
  m.speed_mps = 0.4;
  m.steering_rad = -0.2;
  m.pause_sources = 3;
  m.pause_engaged = 1;
  m.ticks_left = 1LL << 40;
  m.ticks_right = -7;
  const json j = convert(kSimPoseChannel, m);
  EXPECT_EQ(j["channel"], "SIM_DATA_POSE");
  EXPECT_EQ(j["utime"], 9);
  EXPECT_DOUBLE_EQ(j["sim_time_s"].get<double>(), 12.5);
  EXPECT_DOUBLE_EQ(j["x_m"].get<double>(), 2.5);
  EXPECT_DOUBLE_EQ(j["y_m"].get<double>(), -1.25);
  EXPECT_DOUBLE_EQ(j["heading_rad"].get<double>(), 1.5);
  EXPECT_DOUBLE_EQ(j["speed_mps"].get<double>(), 0.4);
  EXPECT_DOUBLE_EQ(j["steering_rad"].get<double>(), -0.2);
  EXPECT_EQ(j["pause_sources"], 3);
  EXPECT_EQ(j["pause_engaged"], true);
  EXPECT_EQ(j["ticks_left"], 1LL << 40);
  EXPECT_EQ(j["ticks_right"], -7);
  const auto bridged = bridged_channels();
  EXPECT_NE(std::find(bridged.begin(), bridged.end(), "SIM_DATA_POSE"), bridged.end());
}
#endif

TEST(MessageJson, EveryRobotChannelIsBridged) {
  const auto bridged = bridged_channels();
  for (const auto& ch : msgs::kAllChannels)
    EXPECT_NE(std::find(bridged.begin(), bridged.end(), std::string(ch.name)), bridged.end())
        << ch.name;
}

TEST(MessageJson, WrongTypeOrTruncatedIsRefused) {
  common::data_state_t s{};
  s.utime = 1;
  s.module = "driver_aux";
  s.state = 3;
  const auto buf = encode(s);
  // A data_state_t on the temperature channel: the fingerprint differs.
  EXPECT_FALSE(message_to_json(msgs::kDataTemperature.name, buf.data(), buf.size()));
  EXPECT_FALSE(message_to_json(msgs::kDataState.name, buf.data(), buf.size() - 1));
  EXPECT_FALSE(message_to_json("NO_SUCH_CHANNEL", buf.data(), buf.size()));
  EXPECT_TRUE(message_to_json(msgs::kDataState.name, buf.data(), buf.size()));
}

TEST(MessageJson, ReplaceKeySeparatesModules) {
  EXPECT_EQ(replace_key({{"channel", "CM_DATA_STATE"}, {"module", "driver_aux"}}), "CM_DATA_STATE/driver_aux");
  EXPECT_EQ(replace_key({{"channel", "CM_DATA_MODULES"}, {"module", "advee-watchdog"}, {"target", "x"}}),
            "CM_DATA_MODULES/x");
  EXPECT_EQ(replace_key({{"channel", "CM_DATA_ERROR"}, {"module", "m"}}), "CM_DATA_ERROR/m");
  EXPECT_EQ(replace_key({{"channel", "LL_DATA_ODO"}, {"module", "driver_rs485a"}}), "LL_DATA_ODO");
}

}  // namespace
}  // namespace advee::web
