// SPDX-License-Identifier: GPL-2.0
#include "advee/pose_integrator.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

using advee::PoseIntegrator;
using advee::wrap_angle;
constexpr double kPi = std::numbers::pi;

TEST(PoseIntegrator, StraightAheadAtFourHertz) {
  PoseIntegrator p;
  for (int i = 0; i < 40; ++i) p.advance(0.5, 0, 0.25);  // 10 s at 0.5 m/s
  EXPECT_NEAR(p.pose().x_m, 5.0, 1e-9);
  EXPECT_NEAR(p.pose().y_m, 0.0, 1e-9);
  EXPECT_NEAR(p.distance_m(), 5.0, 1e-9);
}

TEST(PoseIntegrator, FullCircleReturnsToTheStart) {
  PoseIntegrator p;
  const double w = 0.5, v = 0.5;  // radius 1 m
  const double period = 2 * kPi / w;
  for (int i = 0; i < 50; ++i) {
    p.advance(v, w, period / 50);
    if (i == 24) {  // half way: opposite side of the circle, facing back
      EXPECT_NEAR(p.pose().x_m, 0.0, 1e-9);
      EXPECT_NEAR(p.pose().y_m, 2.0, 1e-9);
      EXPECT_NEAR(std::abs(p.pose().heading_rad), kPi, 1e-9);
    }
  }
  EXPECT_NEAR(p.pose().x_m, 0.0, 1e-9);
  EXPECT_NEAR(p.pose().y_m, 0.0, 1e-9);
  EXPECT_NEAR(p.pose().heading_rad, 0.0, 1e-9);
  EXPECT_NEAR(p.distance_m(), 2 * kPi, 1e-9);
}

// 2 m straight, a left quarter turn of radius 1 m, 1 m straight: (3, 2)
// facing +y; then 1 m in reverse: (3, 1).
TEST(PoseIntegrator, KnownPathWithTurnAndReverse) {
  PoseIntegrator p;
  for (int i = 0; i < 16; ++i) p.advance(0.5, 0, 0.25);
  const double w = 0.4, v = 0.4;  // radius 1 m
  const double quarter = (kPi / 2) / w;
  for (int i = 0; i < 20; ++i) p.advance(v, w, quarter / 20);
  for (int i = 0; i < 8; ++i) p.advance(0.5, 0, 0.25);
  EXPECT_NEAR(p.pose().x_m, 3.0, 1e-9);
  EXPECT_NEAR(p.pose().y_m, 2.0, 1e-9);
  EXPECT_NEAR(p.pose().heading_rad, kPi / 2, 1e-9);
  for (int i = 0; i < 4; ++i) p.advance(-1.0, 0, 0.25);
  EXPECT_NEAR(p.pose().x_m, 3.0, 1e-9);
  EXPECT_NEAR(p.pose().y_m, 1.0, 1e-9);
  EXPECT_NEAR(p.distance_m(), 2 + kPi / 2 + 1 + 1, 1e-9);
}

TEST(PoseIntegrator, BrokenIntervalsAreIgnored) {
  PoseIntegrator p;
  p.advance(1.0, 0, 0.5);
  p.advance(1.0, 0, 0);
  p.advance(1.0, 0, -1);
  p.advance(1.0, 0, std::nan(""));
  p.advance(std::nan(""), 0, 0.25);
  p.advance(1.0, std::numeric_limits<double>::infinity(), 0.25);
  EXPECT_NEAR(p.pose().x_m, 0.5, 1e-12);
  p.reset();
  EXPECT_EQ(p.pose().x_m, 0);
  EXPECT_EQ(p.distance_m(), 0);
}

TEST(PoseIntegrator, WrapAngle) {
  EXPECT_NEAR(wrap_angle(3 * kPi / 2), -kPi / 2, 1e-12);
  EXPECT_NEAR(wrap_angle(-3 * kPi / 2), kPi / 2, 1e-12);
  EXPECT_NEAR(wrap_angle(-kPi), kPi, 1e-12);
  EXPECT_NEAR(wrap_angle(0.25), 0.25, 1e-12);
}
