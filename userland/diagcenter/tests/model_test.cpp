// SPDX-License-Identifier: GPL-2.0
// The model fed with encoded messages as they arrive on the bus.
#include "advee/diagcenter/model.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "common/data_module_phase_t.hpp"
#include "common/data_state_t.hpp"
#include "encode.hpp"
#include "sim/data_pose_t.hpp"

using namespace advee::diagcenter;
using advee::diagcenter::test::encode;
using advee::module::State;

namespace {

common::data_state_t announce(const std::string& name, State s, int pid) {
  common::data_state_t d{};
  d.module = name;
  d.state = static_cast<std::int8_t>(s);
  d.pid = pid;
  return d;
}

common::data_module_phase_t phase(const std::string& target, int ph, int pid, int restarts,
                                  int exit_status) {
  common::data_module_phase_t p{};
  p.module = "watchdog";
  p.target = target;
  p.phase = static_cast<std::int8_t>(ph);
  p.pid = pid;
  p.restarts = restarts;
  p.exit_status = exit_status;
  p.next_start_ms = -1;
  return p;
}

lowlevel::data_odo_t odo(double v, double w, double dt) {
  lowlevel::data_odo_t o{};
  o.module = "driver_rs485a";
  o.speed_mps = v;
  o.yaw_rate_radps = w;
  o.interval_s = dt;
  return o;
}

}  // namespace

TEST(Model, ModulesMergeAnnouncementsAndSupervisor) {
  Model m;
  EXPECT_TRUE(test::feed(m, "CM_DATA_STATE", announce("driver_aux", State::Run, 100), 1.0));
  EXPECT_TRUE(test::feed(m, "CM_DATA_STATE", announce("driver_power", State::Pause, 200), 1.1));
  ASSERT_EQ(m.modules().size(), 2u);
  const auto& aux = m.modules().at("driver_aux");
  EXPECT_EQ(aux.state, State::Run);
  EXPECT_EQ(aux.pid, 100);
  EXPECT_EQ(aux.restarts, -1);  // the supervisor has said nothing yet
  EXPECT_EQ(m.modules().at("driver_power").state, State::Pause);

  // SIGSTOP of driver_aux: the supervisor ends it and starts a new one.
  test::feed(m, "CM_DATA_MODULES", phase("driver_aux", 3, 100, 0, -1), 4.0);
  EXPECT_EQ(m.modules().at("driver_aux").phase, 3);
  test::feed(m, "CM_DATA_MODULES", phase("driver_aux", 4, 0, 0, 143), 4.1);
  test::feed(m, "CM_DATA_MODULES", phase("driver_aux", 1, 101, 1, 143), 4.2);
  test::feed(m, "CM_DATA_STATE", announce("driver_aux", State::Run, 101), 4.5);
  test::feed(m, "CM_DATA_MODULES", phase("driver_aux", 2, 101, 1, 143), 4.5);
  const auto& a2 = m.modules().at("driver_aux");
  EXPECT_EQ(a2.pid, 101);
  EXPECT_EQ(a2.restarts, 1);
  EXPECT_EQ(a2.exit_status, 143);
  EXPECT_EQ(a2.phase, 2);
  EXPECT_STREQ(phase_name(a2.phase), "RUNNING");
  EXPECT_EQ(a2.pids_seen, 2);
  EXPECT_EQ(a2.state_at, 4.5);
  // A module known only through the supervisor (never announced) is listed.
  test::feed(m, "CM_DATA_MODULES", phase("driver_canbus", 0, 0, 3, 33), 5.0);
  ASSERT_EQ(m.modules().count("driver_canbus"), 1u);
  EXPECT_FALSE(m.modules().at("driver_canbus").state.has_value());
}

// The robot drives 2 m straight, a left quarter circle of 1 m radius and
// 1 m straight, reported at 4 Hz as driver_rs485 does: the estimate ends at
// (3, 2) facing +y.
TEST(Model, OdometryIntegratesSpeedAndYawRate) {
  Model m;
  double t = 0;
  for (int i = 0; i < 16; ++i) test::feed(m, "LL_DATA_ODO", odo(0.5, 0, 0.25), t += 0.25);
  const double quarter_s = (std::numbers::pi / 2) / 0.4;
  for (int i = 0; i < 10; ++i) test::feed(m, "LL_DATA_ODO", odo(0.4, 0.4, quarter_s / 10), t += 0.4);
  for (int i = 0; i < 8; ++i) test::feed(m, "LL_DATA_ODO", odo(0.5, 0, 0.25), t += 0.25);
  const auto& p = m.odometry().pose();
  EXPECT_NEAR(p.x_m, 3.0, 1e-6);
  EXPECT_NEAR(p.y_m, 2.0, 1e-6);
  EXPECT_NEAR(p.heading_rad, std::numbers::pi / 2, 1e-6);
  EXPECT_EQ(m.odo().msg.speed_mps, 0.5);
  EXPECT_EQ(m.messages(), 34u);
  m.reset_odometry();
  EXPECT_EQ(m.odometry().pose().x_m, 0);
}

TEST(Model, ErrorsAreKeptNewestLastAndBounded) {
  Model m;
  for (int i = 0; i < 250; ++i) {
    common::error_t e{};
    e.module = "driver_rs485a";
    e.number = i;
    e.text = "error " + std::to_string(i);
    test::feed(m, "CM_DATA_ERROR", e, i);
  }
  EXPECT_EQ(m.errors_total(), 250u);
  ASSERT_EQ(m.errors().size(), Model::kMaxErrors);
  EXPECT_EQ(m.errors().front().msg.number, 50);
  EXPECT_EQ(m.errors().back().msg.text, "error 249");
  EXPECT_EQ(m.errors().back().at, 249);
  m.clear_errors();
  EXPECT_TRUE(m.errors().empty());
  EXPECT_EQ(m.errors_total(), 250u);
}

TEST(Model, LatestSensorDataAndGarbage) {
  Model m;
  lowlevel::data_srfs_t s{};
  s.num_srfs = 2;
  s.srf_id = {0, 5};
  s.srf_range_m = {1.25f, -1.0f};
  s.num_irs = 1;
  s.ir_id = {3};
  s.ir_range_m = {0.12f};
  EXPECT_TRUE(test::feed(m, "LL_DATA_SRFS", s, 2.0));
  lowlevel::data_temperature_t tt{};
  tt.count = 1;
  tt.label = {"temp1"};
  tt.celsius = {31.5f};
  EXPECT_TRUE(test::feed(m, "LL_DATA_TEMPERATURE", tt, 2.5));
  lowlevel::data_drives_t d{};
  d.num_drives = 1;
  d.axis = {lowlevel::data_drives_t::AXIS_PROPULSION};
  d.node = {1};
  d.state = {"operation enabled"};
  d.fault = {false};
  d.error_code = {0};
  d.homed = {false};
  d.speed_mps = 0.29;
  EXPECT_TRUE(test::feed(m, "LL_DATA_DRIVES", d, 3.0));

  // Bytes that are not the channel's type: counted, the previous data stays.
  const std::uint8_t junk[] = {1, 2, 3, 4, 5, 6, 7, 8, 9};
  EXPECT_FALSE(m.handle("LL_DATA_SRFS", junk, sizeof junk, 3.5));
  const auto temps_bytes = encode(tt);  // a valid message on the wrong channel
  EXPECT_FALSE(m.handle("LL_DATA_SRFS", temps_bytes.data(), temps_bytes.size(), 3.6));
  EXPECT_EQ(m.decode_failures(), 2u);
  EXPECT_EQ(m.srfs().at, 2.0);
  EXPECT_EQ(m.srfs().msg.srf_range_m[0], 1.25f);
  EXPECT_EQ(m.srfs().msg.ir_id[0], 3);
  EXPECT_EQ(m.temperatures().msg.celsius[0], 31.5f);
  EXPECT_EQ(m.drives().msg.state[0], "operation enabled");
  EXPECT_DOUBLE_EQ(m.srfs().age(4.0), 2.0);

  EXPECT_FALSE(m.handle("SOMEONE_ELSES", junk, sizeof junk, 4.0));
  EXPECT_EQ(m.decode_failures(), 2u);  // not ours: not a failure
  EXPECT_EQ(m.messages(), 3u);
}

TEST(Model, PauseIsTheNewestOfEventAndPowerStatus) {
  Model m;
  EXPECT_FALSE(m.pause_engaged().has_value());
  lowlevel::data_power_t p{};
  p.num_outputs = 0;
  p.paused = false;
  test::feed(m, "LL_DATA_POWER", p, 1.0);
  EXPECT_EQ(m.pause_engaged(), false);
  lowlevel::event_stop_t e{};
  e.stop = true;
  test::feed(m, "LL_EVENT_STOP", e, 1.5);  // between two 1 Hz status messages
  EXPECT_EQ(m.pause_engaged(), true);
  p.paused = true;
  test::feed(m, "LL_DATA_POWER", p, 2.0);
  EXPECT_EQ(m.pause_engaged(), true);
  e.stop = false;
  test::feed(m, "LL_EVENT_STOP", e, 2.2);
  EXPECT_EQ(m.pause_engaged(), false);
}

TEST(Model, StaleAfterThreePeriods) {
  EXPECT_DOUBLE_EQ(stale_after_s(4.0), 1.5);  // at least 1.5 s
  EXPECT_DOUBLE_EQ(stale_after_s(1.0), 3.0);
  EXPECT_TRUE(std::isinf(stale_after_s(0)));  // commands are never stale
}

// Through LCM itself (in-process memq://): every subscribed channel reaches
// the model with the clock's time.
TEST(Model, SubscribesEveryChannelOnLcm) {
  lcm::LCM lcm("memq://");
  ASSERT_TRUE(lcm.good());
  Model m;
  m.subscribe(lcm, [] { return 42.0; });
  const auto chans = model_channels();
  EXPECT_GE(chans.size(), 16u);
  auto st = announce("driver_aux", State::Run, 7);
  lcm.publish("CM_DATA_STATE", &st);
  lowlevel::cmd_motion_t c{};
  c.module = "planner";
  c.speed_mps = 0.3;
  c.steering_rad = -0.1;
  lcm.publish("LL_CMD_MOTION", &c);
  lowlevel::data_fans_t f{};
  f.count = 1;
  f.label = {"fan1"};
  f.rpm = {1500};
  f.fault = {false};
  f.pwm = {128};
  lcm.publish("LL_DATA_FANS", &f);
  while (lcm.handleTimeout(0) > 0) {
  }
  EXPECT_EQ(m.messages(), 3u);
  EXPECT_EQ(m.modules().at("driver_aux").state_at, 42.0);
  EXPECT_EQ(m.motion_cmd().msg.speed_mps, 0.3);
  EXPECT_EQ(m.motion_cmd().msg.module, "planner");
  EXPECT_EQ(m.fans().msg.rpm[0], 1500);
}

// On the simulated robot the estimate starts at the first ground truth and
// integrates from there; later true poses do not move it (it is an estimate,
// not a copy); a reset goes back to the newest true pose.
TEST(Model, OdometryStartsAtTheFirstTruePose) {
  Model m;
  EXPECT_FALSE(m.odometry_from_true_pose());
  sim::data_pose_t p{};
  p.x_m = 2.0;
  p.y_m = 1.0;
  p.heading_rad = std::numbers::pi;  // facing -x
  EXPECT_TRUE(test::feed(m, "SIM_DATA_POSE", p, 1.0));
  EXPECT_TRUE(m.odometry_from_true_pose());
  EXPECT_TRUE(m.true_pose().has());
  test::feed(m, "LL_DATA_ODO", odo(1.0, 0, 0.5), 1.5);
  EXPECT_NEAR(m.odometry().pose().x_m, 1.5, 1e-12);
  EXPECT_NEAR(m.odometry().pose().y_m, 1.0, 1e-12);
  p.x_m = 1.45;  // the truth differs a little (wheel slip)
  test::feed(m, "SIM_DATA_POSE", p, 1.6);
  EXPECT_NEAR(m.odometry().pose().x_m, 1.5, 1e-12);
  EXPECT_EQ(m.true_pose().x_m, 1.45);
  m.reset_odometry();
  EXPECT_EQ(m.odometry().pose().x_m, 1.45);
}
