// SPDX-License-Identifier: GPL-2.0
// Keys -> commands, as the operator would press them.
#include "advee/diagcenter/controller.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <vector>

#include "common/data_state_t.hpp"
#include "encode.hpp"

using namespace advee::diagcenter;
using advee::module::State;

namespace {

constexpr double kDeg = std::numbers::pi / 180;

struct Recorder final : CommandSink {
  struct Motion {
    double v, s;
  };
  std::vector<Motion> motions;
  std::vector<std::pair<std::string, State>> states;
  std::vector<std::pair<int, bool>> outputs;
  int homings = 0;
  bool motion(double v, double s) override {
    motions.push_back({v, s});
    return true;
  }
  bool state(const std::string& t, State s) override {
    states.emplace_back(t, s);
    return true;
  }
  bool power_output(int o, bool on) override {
    outputs.emplace_back(o, on);
    return true;
  }
  bool homing_steering() override {
    ++homings;
    return true;
  }
};

const Key kUp{Key::Up}, kDown{Key::Down}, kLeft{Key::Left}, kRight{Key::Right}, kEnter{Key::Enter};

}  // namespace

TEST(Controller, ArrowsDriveAndCommandsRepeatAtTenHertz) {
  Model m;
  Recorder r;
  Controller c(m, r);
  EXPECT_FALSE(c.manual());
  c.tick(0.0);
  EXPECT_TRUE(r.motions.empty());  // nothing is sent before the operator drives

  c.on_key(kUp, 0.0);
  ASSERT_EQ(r.motions.size(), 1u);  // at once, not at the next tick
  EXPECT_TRUE(c.manual());
  EXPECT_DOUBLE_EQ(r.motions[0].v, 0.1);
  EXPECT_DOUBLE_EQ(r.motions[0].s, 0.0);
  c.on_key(kUp, 0.0);
  c.on_key(kLeft, 0.0);
  EXPECT_DOUBLE_EQ(r.motions.back().v, 0.2);
  EXPECT_NEAR(r.motions.back().s, 5 * kDeg, 1e-12);

  // Ticks every 10 ms until 1 s after the last key: 9 repeats, with the
  // key's own command 10 per second, each the current one.
  const auto before = r.motions.size();
  for (int i = 0; i < 100; ++i) c.tick(0.005 + i * 0.01);
  EXPECT_EQ(r.motions.size() - before, 9u);
  EXPECT_DOUBLE_EQ(r.motions.back().v, 0.2);
  EXPECT_NEAR(r.motions.back().s, 5 * kDeg, 1e-12);
  // Coarse ticks (a busy terminal) do not lower the rate: every 30 ms for 3 s.
  const auto before_coarse = r.motions.size();
  for (int i = 0; i < 100; ++i) c.tick(1.0 + i * 0.03);
  EXPECT_EQ(r.motions.size() - before_coarse, 30u);

  c.on_key(kRight, 2.0);
  c.on_key(kRight, 2.0);
  EXPECT_NEAR(c.steering_rad(), -5 * kDeg, 1e-12);
  c.on_key(kDown, 2.0);
  c.on_key(kDown, 2.0);
  c.on_key(kDown, 2.0);
  EXPECT_DOUBLE_EQ(c.speed_mps(), -0.1);  // down past zero reverses
  EXPECT_NE(c.status().find("-0.10 m/s"), std::string::npos);
}

TEST(Controller, LimitsClampSpeedAndSteering) {
  Model m;
  Recorder r;
  Controller c(m, r, DriveLimits{0.25, 1.0, 10 * kDeg, 30 * kDeg});
  for (int i = 0; i < 10; ++i) c.on_key(kUp, 0);
  EXPECT_DOUBLE_EQ(c.speed_mps(), 1.0);
  for (int i = 0; i < 10; ++i) c.on_key(kLeft, 0);
  EXPECT_NEAR(c.steering_rad(), 30 * kDeg, 1e-12);
  for (int i = 0; i < 20; ++i) c.on_key(kRight, 0);
  EXPECT_NEAR(c.steering_rad(), -30 * kDeg, 1e-12);
  for (int i = 0; i < 20; ++i) c.on_key(kDown, 0);
  EXPECT_DOUBLE_EQ(r.motions.back().v, -1.0);
}

TEST(Controller, SpaceStopsInEveryViewAndMTurnsManualOff) {
  Model m;
  Recorder r;
  Controller c(m, r);
  c.on_key(kUp, 0);
  c.on_key(kLeft, 0);
  c.on_key(Key::ch('3'), 0);  // module view: the drive goes on
  EXPECT_EQ(c.view(), View::Modules);
  c.tick(0.5);
  EXPECT_DOUBLE_EQ(r.motions.back().v, 0.1);
  c.on_key(Key::ch(' '), 0.55);
  EXPECT_DOUBLE_EQ(r.motions.back().v, 0.0);
  EXPECT_DOUBLE_EQ(r.motions.back().s, 0.0);
  EXPECT_TRUE(c.manual());  // still publishing: the zero command keeps the drives held

  c.on_key(Key::fn(1), 1.0);
  EXPECT_EQ(c.view(), View::Summary);
  c.on_key(Key::ch('m'), 1.0);  // off: one zero command, then silence
  EXPECT_FALSE(c.manual());
  const auto n = r.motions.size();
  EXPECT_DOUBLE_EQ(r.motions.back().v, 0.0);
  for (int i = 0; i < 20; ++i) c.tick(1.0 + i * 0.1);
  EXPECT_EQ(r.motions.size(), n);
  c.on_key(Key::ch('m'), 5.0);  // on again from standstill
  EXPECT_TRUE(c.manual());
  EXPECT_DOUBLE_EQ(r.motions.back().v, 0.0);
}

TEST(Controller, QuitStopsAManualDrive) {
  Model m;
  Recorder r;
  Controller c(m, r);
  c.on_key(kUp, 0);
  c.on_key(Key::ch('q'), 0.05);
  EXPECT_TRUE(c.quit());
  EXPECT_DOUBLE_EQ(r.motions.back().v, 0.0);
  const auto n = r.motions.size();
  c.tick(1.0);
  EXPECT_EQ(r.motions.size(), n);
}

TEST(Controller, HomingAndOdometryReset) {
  Model m;
  Recorder r;
  Controller c(m, r);
  c.on_key(Key::ch('h'), 0);
  EXPECT_EQ(r.homings, 1);
  lowlevel::data_odo_t o{};
  o.speed_mps = 1;
  o.interval_s = 0.25;
  test::feed(m, "LL_DATA_ODO", o, 0.1);
  EXPECT_NEAR(m.odometry().pose().x_m, 0.25, 1e-12);
  c.on_key(Key::ch('o'), 0.2);
  EXPECT_EQ(m.odometry().pose().x_m, 0);
  c.on_key(Key::ch('2'), 0.2);  // 'h' in another view does not home
  c.on_key(Key::ch('h'), 0.2);
  EXPECT_EQ(r.homings, 1);
}

TEST(Controller, ModuleViewSendsManualStateCommandsToTheSelectedModule) {
  Model m;
  Recorder r;
  Controller c(m, r);
  for (const char* name : {"driver_aux", "driver_power", "driver_rs485a"}) {
    common::data_state_t s{};
    s.module = name;
    s.state = static_cast<std::int8_t>(State::Run);
    s.pid = 1;
    test::feed(m, "CM_DATA_STATE", s, 0);
  }
  c.on_key(Key::fn(3), 0);
  EXPECT_EQ(c.selected_module(), "driver_aux");
  c.on_key(kDown, 0);
  c.on_key(Key::ch('s'), 0);
  c.on_key(kDown, 0);
  c.on_key(kDown, 0);  // stays on the last row
  c.on_key(Key::ch('p'), 0);
  c.on_key(kUp, 0);
  c.on_key(kUp, 0);
  c.on_key(kUp, 0);
  c.on_key(Key::ch('t'), 0);  // asks for confirmation first
  EXPECT_EQ(r.states.size(), 2u);
  EXPECT_EQ(c.status(), "press t again to TERMINATE driver_aux");
  c.on_key(Key::ch('t'), 1.0);
  c.on_key(Key::ch('r'), 1.0);
  ASSERT_EQ(r.states.size(), 4u);
  EXPECT_EQ(r.states[0], std::make_pair(std::string("driver_power"), State::Stop));
  EXPECT_EQ(r.states[1], std::make_pair(std::string("driver_rs485a"), State::Pause));
  EXPECT_EQ(r.states[2], std::make_pair(std::string("driver_aux"), State::Terminate));
  EXPECT_EQ(r.states[3], std::make_pair(std::string("driver_aux"), State::Run));
  EXPECT_TRUE(r.motions.empty());  // arrows select here, they do not drive
}

TEST(Controller, TerminateNeedsASecondTOnTheSameModuleInTime) {
  Model m;
  Recorder r;
  Controller c(m, r);
  for (const char* name : {"driver_aux", "watchdog"}) {
    common::data_state_t s{};
    s.module = name;
    s.state = static_cast<std::int8_t>(State::Run);
    test::feed(m, "CM_DATA_STATE", s, 0);
  }
  c.on_key(Key::ch('3'), 0);
  c.on_key(Key::ch('t'), 0);
  c.on_key(Key::ch('t'), 3.5);  // too late: asks again
  c.on_key(kDown, 3.6);
  c.on_key(Key::ch('t'), 3.7);  // another module: asks again
  EXPECT_TRUE(r.states.empty());
  EXPECT_EQ(c.status(), "press t again to TERMINATE watchdog");
  c.on_key(Key::ch('t'), 4.0);
  ASSERT_EQ(r.states.size(), 1u);
  EXPECT_EQ(r.states[0], std::make_pair(std::string("watchdog"), State::Terminate));
  c.on_key(Key::ch('t'), 4.1);  // a third t starts over
  EXPECT_EQ(r.states.size(), 1u);
}

TEST(Controller, ModuleCommandWithoutModulesSendsNothing) {
  Model m;
  Recorder r;
  Controller c(m, r);
  c.on_key(Key::ch('3'), 0);
  c.on_key(Key::ch('s'), 0);
  EXPECT_TRUE(r.states.empty());
  EXPECT_EQ(c.status(), "no module to command");
}

TEST(Controller, PowerViewTogglesTheSelectedOutput) {
  Model m;
  Recorder r;
  Controller c(m, r);
  lowlevel::data_power_t p{};
  p.num_outputs = 4;
  p.on = {true, true, false, false};
  p.current_a = {0.5f, 0.2f, -1.0f, -1.0f};
  test::feed(m, "LL_DATA_POWER", p, 0);
  c.on_key(Key::fn(4), 0);
  EXPECT_EQ(c.view(), View::Power);
  c.on_key(kDown, 0);
  c.on_key(kEnter, 0);  // output 1 is on -> off
  c.on_key(kDown, 0);
  c.on_key(kEnter, 0);  // output 2 is off -> on
  for (int i = 0; i < 10; ++i) c.on_key(kDown, 0);
  EXPECT_EQ(c.power_row(), 3);  // the board has 4 outputs
  c.on_key(Key::ch('n'), 0);
  c.on_key(Key::ch('f'), 0);
  ASSERT_EQ(r.outputs.size(), 4u);
  EXPECT_EQ(r.outputs[0], std::make_pair(1, false));
  EXPECT_EQ(r.outputs[1], std::make_pair(2, true));
  EXPECT_EQ(r.outputs[2], std::make_pair(3, true));
  EXPECT_EQ(r.outputs[3], std::make_pair(3, false));
}

TEST(Controller, ErrorViewScrollsAndClears) {
  Model m;
  Recorder r;
  Controller c(m, r);
  for (int i = 0; i < 3; ++i) {
    common::error_t e{};
    e.text = "e" + std::to_string(i);
    test::feed(m, "CM_DATA_ERROR", e, i);
  }
  c.on_key(Key::ch('2'), 0);
  for (int i = 0; i < 5; ++i) c.on_key(kUp, 0);
  EXPECT_EQ(c.error_scroll(), 2u);  // the oldest stays on screen
  c.on_key(kDown, 0);
  EXPECT_EQ(c.error_scroll(), 1u);
  c.on_key(Key::ch('c'), 0);
  EXPECT_TRUE(m.errors().empty());
  EXPECT_EQ(c.error_scroll(), 0u);
}
