// SPDX-License-Identifier: GPL-2.0
// The chassis kinematics: ticks to metres, straight runs, turns on both
// sides and in reverse (inverse of the forward model), the rear-axle
// variant, and invalid geometry.
#include <gtest/gtest.h>

#include <chrono>
#include <cmath>
#include <numbers>
#include <stdexcept>

#include "advee/driver_rs485/odometry.hpp"

using namespace advee::driver_rs485;

namespace {

ChassisGeometry robot() {
  ChassisGeometry g;
  g.wheel_radius_m = 0.125;
  g.ticks_per_rev = 2048;
  g.track_m = 0.52;
  g.wheelbase_m = 0.62;
  return g;
}

}  // namespace

TEST(Odometry, OneRevolutionIsTheWheelCircumference) {
  AckermannOdometry o(robot());
  EXPECT_DOUBLE_EQ(o.metres_per_tick() * 2048, 2 * std::numbers::pi * 0.125);
  // 2048 ticks per second on both wheels: straight ahead at 0.785 m/s.
  const auto s = o.from_ticks(2048, 2048, 1.0);
  EXPECT_NEAR(s.speed_mps, 0.7853981634, 1e-9);
  EXPECT_NEAR(s.yaw_rate_radps, 0.0, 1e-12);
  // The same distance over half the time is twice the speed.
  EXPECT_NEAR(o.from_ticks(1024, 1024, 0.25).speed_mps, 2 * 0.7853981634, 1e-9);
  const auto back = o.from_ticks(-512, -512, 0.25);
  EXPECT_NEAR(back.speed_mps, -0.7853981634, 1e-9);
  EXPECT_NEAR(back.yaw_rate_radps, 0.0, 1e-12);
}

TEST(Odometry, StandingStillIsZero) {
  AckermannOdometry o(robot());
  const auto s = o.from_ticks(0, 0, 0.25);
  EXPECT_EQ(s.speed_mps, 0.0);
  EXPECT_EQ(s.yaw_rate_radps, 0.0);
}

TEST(Odometry, FrontWheelsOfATurnGiveBackTheBodySpeed) {
  AckermannOdometry o(robot());
  // A left turn with the centre of rotation 2 m to the left of the rear axle:
  // v = 1 m/s, w = 0.5 rad/s. The outer (right) front wheel is faster.
  for (const BodySpeed want : {BodySpeed{1.0, 0.5}, BodySpeed{1.0, -0.5}, BodySpeed{-0.4, 0.3},
                               BodySpeed{-0.4, -0.3}, BodySpeed{0.5, 0.6}}) {
    const auto w = o.wheel_speeds(want);
    const auto got = o.from_wheel_speeds(w.x(), w.y());
    EXPECT_NEAR(got.speed_mps, want.speed_mps, 1e-9) << want.speed_mps << " " << want.yaw_rate_radps;
    EXPECT_NEAR(got.yaw_rate_radps, want.yaw_rate_radps, 1e-9) << want.speed_mps << " " << want.yaw_rate_radps;
  }
  const auto left_turn = o.wheel_speeds({1.0, 0.5});
  EXPECT_GT(left_turn.y(), left_turn.x());
  // Front-left wheel of that turn: distance to (0, 2) is sqrt(0.62^2 + 1.74^2).
  EXPECT_NEAR(left_turn.x(), 0.5 * std::hypot(0.62, 2.0 - 0.26), 1e-12);
  EXPECT_NEAR(left_turn.y(), 0.5 * std::hypot(0.62, 2.0 + 0.26), 1e-12);
}

TEST(Odometry, TightestTurnThatInvertsUniquely) {
  // Below a turn radius of sqrt(L^2 + T^2/4) = 0.672 m (inner wheel steered
  // more than 56 degrees, beyond the robot's steering) two body speeds give
  // the same wheel speeds; just above it the inversion is still exact.
  AckermannOdometry o(robot());
  const BodySpeed want{0.68, 1.0};
  const auto w = o.wheel_speeds(want);
  const auto got = o.from_wheel_speeds(w.x(), w.y());
  EXPECT_NEAR(got.speed_mps, want.speed_mps, 1e-6);
  EXPECT_NEAR(got.yaw_rate_radps, want.yaw_rate_radps, 1e-6);
}

TEST(Odometry, SteeredWheelsAreNotADifferentialDrive) {
  // The front wheels of a turn roll farther than the rear axle: the
  // differential formula would overestimate the speed.
  AckermannOdometry o(robot());
  const auto w = o.wheel_speeds({1.0, 0.8});
  EXPECT_GT((w.x() + w.y()) / 2, 1.02);
  EXPECT_NEAR(o.from_wheel_speeds(w.x(), w.y()).speed_mps, 1.0, 1e-9);
}

TEST(Odometry, RearEncodersAreADifferentialDrive) {
  auto g = robot();
  g.encoders_on_front = false;
  AckermannOdometry o(g);
  const auto s = o.from_wheel_speeds(0.74, 1.26);
  EXPECT_NEAR(s.speed_mps, 1.0, 1e-12);
  EXPECT_NEAR(s.yaw_rate_radps, 1.0, 1e-12);
  const auto w = o.wheel_speeds({1.0, 1.0});
  EXPECT_NEAR(w.x(), 0.74, 1e-12);
  EXPECT_NEAR(w.y(), 1.26, 1e-12);
}

TEST(Odometry, InvalidGeometryAndIntervalAreRejected) {
  auto g = robot();
  g.ticks_per_rev = 0;
  EXPECT_THROW(AckermannOdometry{g}, std::invalid_argument);
  g = robot();
  g.track_m = -1;
  EXPECT_THROW(AckermannOdometry{g}, std::invalid_argument);
  AckermannOdometry o(robot());
  EXPECT_THROW(o.from_ticks(10, 10, 0), std::invalid_argument);
}

TEST(Odometry, UnambiguousGapIsHalfTheCounterRangeAtTopSpeed) {
  // 1.5 m/s on 0.125 m wheels with 2048 ticks/rev: 3911.5 ticks/s.
  const double ticks_per_s = 1.5 / (2 * std::numbers::pi * 0.125) * 2048;
  const auto seconds = [](std::chrono::nanoseconds d) { return std::chrono::duration<double>(d).count(); };
  EXPECT_NEAR(seconds(unambiguous_tick_gap(robot(), 2, 1.5)), 32768 / ticks_per_s, 1e-6);  // 8.38 s
  EXPECT_NEAR(seconds(unambiguous_tick_gap(robot(), 1, 1.5)), 128 / ticks_per_s, 1e-6);
  EXPECT_NEAR(seconds(unambiguous_tick_gap(robot(), 4, 1.5)), 2147483648.0 / ticks_per_s, 1e-3);
  // A 2.5 s gap at top speed stays well inside 16-bit counters.
  EXPECT_GT(seconds(unambiguous_tick_gap(robot(), 2, 1.5)), 2.5);
  // Twice as fast: half as long.
  EXPECT_NEAR(seconds(unambiguous_tick_gap(robot(), 2, 3.0)), 16384 / ticks_per_s, 1e-6);
  EXPECT_THROW(unambiguous_tick_gap(robot(), 3, 1.5), std::invalid_argument);
  EXPECT_THROW(unambiguous_tick_gap(robot(), 2, 0), std::invalid_argument);
}
