// SPDX-License-Identifier: GPL-2.0
#include <gtest/gtest.h>

#include <cmath>

#include "advee/robotsim/kinematics.hpp"
#include "advee/robotsim/robot.hpp"
#include "test_util.hpp"

namespace advee::robotsim {
namespace {

TEST(Kinematics, StraightLine) {
  Robot r(test::exact_robot(), test::example_room());  // starts at (2, 2) heading east
  for (int i = 0; i < 1000; ++i) r.step(0.5, 0, 0.01);  // 10 s at 0.5 m/s
  EXPECT_NEAR(r.pose().position.x(), 7.0, 1e-9);
  EXPECT_NEAR(r.pose().position.y(), 2.0, 1e-9);
  EXPECT_NEAR(r.pose().heading, 0, 1e-12);
  // Both front wheels rolled 5 m: 5 / (2 pi 0.125) * 2048 ticks.
  const double expect = 5 / (2 * kPi * 0.125) * 2048;
  EXPECT_NEAR(r.exact_ticks()[0], expect, 1e-6);
  EXPECT_NEAR(r.exact_ticks()[1], expect, 1e-6);
}

TEST(Kinematics, ConstantCurvatureCircleCloses) {
  World open;  // no walls: the circle needs room
  RobotDescription d = test::exact_robot();
  d.start = {{0, 0}, 0.3};
  Robot r(d, open);
  const double steer = deg_to_rad(20), v = 0.4;
  const double radius = 0.62 / std::tan(steer);
  const double period = 2 * kPi * radius / v;
  const int steps = 4000;
  double max_dist = 0;
  for (int i = 0; i < steps; ++i) {
    r.step(v, steer, period / steps);
    max_dist = std::max(max_dist, r.pose().position.norm());
  }
  EXPECT_NEAR(r.pose().position.norm(), 0, 1e-9);
  EXPECT_NEAR(wrap_angle(r.pose().heading - 0.3), 0, 1e-9);
  EXPECT_NEAR(max_dist, 2 * radius, 1e-3);  // the diameter, reached half way
  // The outer (right) front wheel rolls farther than the inner one.
  EXPECT_GT(r.exact_ticks()[1], r.exact_ticks()[0]);
}

TEST(Kinematics, SteeringIsClampedToTheLimit) {
  World open;
  RobotDescription d = test::exact_robot();
  Robot limited(d, open), at_limit(d, open);
  for (int i = 0; i < 100; ++i) {
    limited.step(0.5, deg_to_rad(60), 0.01);
    at_limit.step(0.5, deg_to_rad(30), 0.01);
  }
  EXPECT_NEAR(limited.pose().heading, 0.5 * std::tan(deg_to_rad(30)) / 0.62, 1e-9);
  EXPECT_NEAR((limited.pose().position - at_limit.pose().position).norm(), 0, 1e-12);
  // Speed too: 3 m/s asked, 1.5 m/s driven.
  Robot fast(d, open);
  fast.step(3.0, 0, 1.0);
  EXPECT_NEAR(fast.pose().position.x(), 2 + 1.5, 1e-9);
}

TEST(Kinematics, FrontWheelInversionRoundTrip) {
  for (double steer_deg : {-30.0, -12.0, 0.0, 5.0, 29.0}) {
    for (double v : {-0.4, 0.3, 1.2}) {
      const double w = yaw_rate(v, deg_to_rad(steer_deg), 0.62);
      const auto d = front_wheel_distances(v, w, 0.62, 0.52, 0.25);
      const Motion m = motion_from_front_wheels(d[0], d[1], 0.62, 0.52);
      EXPECT_NEAR(m.distance, v * 0.25, 1e-12) << steer_deg << " deg, " << v << " m/s";
      EXPECT_NEAR(m.heading_change, w * 0.25, 1e-12) << steer_deg << " deg, " << v << " m/s";
    }
  }
}

}  // namespace
}  // namespace advee::robotsim
