// SPDX-License-Identifier: GPL-2.0
// The --text block: the lines scripts grep must be there and say the truth.
#include "advee/diagcenter/text_summary.hpp"

#include <gtest/gtest.h>

#include <sstream>

#include "common/data_module_phase_t.hpp"
#include "common/data_state_t.hpp"
#include "encode.hpp"
#include "sim/data_pose_t.hpp"

using namespace advee::diagcenter;
using advee::module::State;

namespace {

// The line of the block that starts with "topic ".
std::string line(const std::string& block, const std::string& topic) {
  std::istringstream in(block);
  std::string l;
  while (std::getline(in, l))
    if (l.rfind(topic + " ", 0) == 0) return l;
  return "<no line " + topic + ">";
}

}  // namespace

TEST(TextSummary, EmptyModelSaysNone) {
  Model m;
  const auto b = text_summary(m, 10.0, 1.0);
  EXPECT_EQ(line(b, "summary"), "summary t=1.0 messages=0");
  EXPECT_EQ(line(b, "pose_odo"), "pose_odo x=0.000 y=0.000 heading=0.000 distance=0.000 origin=zero age=none");
  EXPECT_EQ(line(b, "pose_true"), "pose_true none");
  EXPECT_EQ(line(b, "motion"), "motion cmd_v=none cmd_steer=none v=none steer=none");
  for (const char* t : {"odo", "drives", "modules", "srf", "ir", "beacons", "temps", "fans",
                        "power", "stop"})
    EXPECT_EQ(line(b, t), std::string(t) + " none");
  EXPECT_EQ(line(b, "errors"), "errors total=0");
}

TEST(TextSummary, EveryTopicWithValuesAndAges) {
  Model m;
  common::data_state_t s{};
  s.module = "driver_aux";
  s.state = static_cast<std::int8_t>(State::Run);
  s.pid = 321;
  ASSERT_TRUE(test::feed(m, "CM_DATA_STATE", s, 9.5)) << "CM_DATA_STATE";
  s.module = "driver_power";
  s.state = static_cast<std::int8_t>(State::Pause);
  s.pid = 322;
  ASSERT_TRUE(test::feed(m, "CM_DATA_STATE", s, 6.0)) << "CM_DATA_STATE";  // 4 s ago: stale
  common::data_module_phase_t ph{};
  ph.target = "driver_aux";
  ph.phase = 2;
  ph.pid = 321;
  ph.restarts = 2;
  ASSERT_TRUE(test::feed(m, "CM_DATA_MODULES", ph, 9.0)) << "CM_DATA_MODULES";

  lowlevel::data_odo_t o{};
  o.speed_mps = 0.5;
  o.yaw_rate_radps = 0;
  o.interval_s = 2.0;
  ASSERT_TRUE(test::feed(m, "LL_DATA_ODO", o, 9.8)) << "LL_DATA_ODO";
  lowlevel::cmd_motion_t c{};
  c.module = "diagnostic_center";
  c.speed_mps = 0.3;
  c.steering_rad = 0.0873;
  ASSERT_TRUE(test::feed(m, "LL_CMD_MOTION", c, 9.9)) << "LL_CMD_MOTION";
  lowlevel::data_drives_t d{};
  d.num_drives = 2;
  d.axis = {0, 1};
  d.node = {1, 2};
  d.state = {"operation enabled", "fault"};
  d.fault = {false, true};
  d.error_code = {0, 0x7500};
  d.homed = {false, true};
  d.speed_mps = 0.29;
  d.steering_rad = 0.08;
  d.cmd_speed_mps = 0.3;
  d.cmd_steering_rad = 0.0873;
  d.stopped = true;
  d.stop_reason = "LL_EVENT_STOP";
  ASSERT_TRUE(test::feed(m, "LL_DATA_DRIVES", d, 9.75)) << "LL_DATA_DRIVES";
  lowlevel::data_srfs_t sr{};
  sr.num_srfs = 2;
  sr.srf_id = {0, 1};
  sr.srf_range_m = {1.5f, -1.0f};
  sr.num_irs = 1;
  sr.ir_id = {2};
  sr.ir_range_m = {0.125f};
  ASSERT_TRUE(test::feed(m, "LL_DATA_SRFS", sr, 9.9)) << "LL_DATA_SRFS";
  lowlevel::data_beacons_t be{};
  be.count = 1;
  be.id = {3};
  be.bearing_rad = {1.5708f};
  ASSERT_TRUE(test::feed(m, "LL_DATA_BEACONS", be, 9.0)) << "LL_DATA_BEACONS";
  lowlevel::data_temperature_t te{};
  te.count = 2;
  te.label = {"temp1", "temp2"};
  te.celsius = {31.5f, 44.125f};
  ASSERT_TRUE(test::feed(m, "LL_DATA_TEMPERATURE", te, 5.0)) << "LL_DATA_TEMPERATURE";  // 5 s ago at 1 Hz: stale
  lowlevel::data_fans_t fa{};
  fa.count = 1;
  fa.label = {"fan1"};
  fa.rpm = {1500};
  fa.fault = {true};
  fa.pwm = {255};
  fa.fan_fail = true;
  ASSERT_TRUE(test::feed(m, "LL_DATA_FANS", fa, 9.5)) << "LL_DATA_FANS";
  lowlevel::data_power_t pw{};
  pw.battery_v = -1;
  pw.num_outputs = 2;
  pw.on = {true, false};
  pw.current_a = {0.5f, -1.0f};
  pw.paused = false;
  ASSERT_TRUE(test::feed(m, "LL_DATA_POWER", pw, 9.0)) << "LL_DATA_POWER";
  lowlevel::event_stop_t st{};
  st.stop = true;
  st.source = lowlevel::event_stop_t::SOURCE_PSC1;
  ASSERT_TRUE(test::feed(m, "LL_EVENT_STOP", st, 9.6)) << "LL_EVENT_STOP";
  common::error_t e{};
  e.module = "driver_rs485a";
  e.number = 1;
  e.severity = common::error_t::SEVERITY_WARNING;
  e.text = "rear (0x11): GET_BOTH failed: timeout";
  ASSERT_TRUE(test::feed(m, "CM_DATA_ERROR", e, 8.0)) << "CM_DATA_ERROR";

  const auto b = text_summary(m, 10.0, 3.0);
  EXPECT_EQ(line(b, "summary"), "summary t=3.0 messages=13");
  EXPECT_EQ(line(b, "pose_odo"), "pose_odo x=1.000 y=0.000 heading=0.000 distance=1.000 origin=zero age=0.2");
  EXPECT_EQ(line(b, "odo"), "odo v=0.500 w=0.000 age=0.2");
  EXPECT_EQ(line(b, "motion"),
            "motion cmd_v=0.300 cmd_steer=0.087 cmd_age=0.1 cmd_from=diagnostic_center v=0.290 "
            "steer=0.080 drives_age=0.2");
  EXPECT_EQ(line(b, "drives"),
            "drives propulsion=operation_enabled propulsion_fault=0 propulsion_homed=0 "
            "steering=fault steering_fault=1 steering_homed=1 cmd_v=0.300 cmd_steer=0.087 "
            "stopped=1 reason=LL_EVENT_STOP age=0.2");
  EXPECT_EQ(line(b, "modules"), "modules driver_aux=RUN driver_power=PAUSE");
  EXPECT_EQ(line(b, "module_pids"), "module_pids driver_aux=321 driver_power=322");
  EXPECT_EQ(line(b, "module_restarts"), "module_restarts driver_aux=2 driver_power=none");
  EXPECT_EQ(line(b, "module_phases"), "module_phases driver_aux=RUNNING driver_power=-");
  EXPECT_EQ(line(b, "module_ages"), "module_ages driver_aux=0.5 driver_power=4.0!");
  EXPECT_EQ(line(b, "srf"), "srf 0=1.500 1=-1.000 age=0.1");
  EXPECT_EQ(line(b, "ir"), "ir 2=0.125 age=0.1");
  EXPECT_EQ(line(b, "beacons"), "beacons count=1 3=1.571 age=1.0");
  EXPECT_EQ(line(b, "temps"), "temps temp1=31.5 temp2=44.1 age=5.0 stale=1");
  EXPECT_EQ(line(b, "fans"), "fans fan1=1500 fan1_fault=1 fan_fail=1 age=0.5");
  EXPECT_EQ(line(b, "power"),
            "power battery=-1.00 out0=on out1=off i0=0.50 i1=-1.00 paused=0 age=1.0");
  // The event is newer than the status: PAUSE is engaged.
  EXPECT_EQ(line(b, "stop"), "stop engaged=1 events_source=psc1 event_age=0.4");
  EXPECT_EQ(line(b, "errors"),
            "errors total=1 last_module=driver_rs485a last_number=1 last_severity=1 last_age=2.0 "
            "last_text=\"rear (0x11): GET_BOTH failed: timeout\"");
}

TEST(TextSummary, TokensStayOneWord) {
  EXPECT_EQ(token("switch on disabled"), "switch_on_disabled");
  EXPECT_EQ(token("a=b"), "a_b");
  EXPECT_EQ(token(""), "-");
}

TEST(TextSummary, TruePoseAndOdometryInTheWorldFrame) {
  Model m;
  sim::data_pose_t p{};
  p.x_m = 1.5;
  p.y_m = 2.0;
  p.heading_rad = 1.5707963267948966;  // facing +y
  p.speed_mps = 0.5;
  p.steering_rad = 0.1;
  ASSERT_TRUE(test::feed(m, "SIM_DATA_POSE", p, 9.9)) << "SIM_DATA_POSE";
  lowlevel::data_odo_t o{};
  o.speed_mps = 0.5;
  o.interval_s = 1.0;
  ASSERT_TRUE(test::feed(m, "LL_DATA_ODO", o, 10.0)) << "LL_DATA_ODO";
  const auto b = text_summary(m, 10.0, 1.0);
  EXPECT_EQ(line(b, "pose_true"),
            "pose_true x=1.500 y=2.000 heading=1.571 speed=0.500 steering=0.100 age=0.1");
  // The estimate continued from the first true pose: 0.5 m along +y.
  EXPECT_EQ(line(b, "pose_odo"),
            "pose_odo x=1.500 y=2.500 heading=1.571 distance=0.500 origin=true age=0.0");
}
