// SPDX-License-Identifier: GPL-2.0
// The demo's odometry check in the small: the BR-SO1 ticks the virtual robot
// generates, integrated as driver_rs485 integrates them, must follow the
// true pose along the example path within the tolerance docs/robotsim.md
// states.
#include <gtest/gtest.h>

#include <cmath>

#include "advee/robotsim/scripted_path.hpp"
#include "test_util.hpp"

namespace advee::robotsim {
namespace {

// Stated tolerance (docs/robotsim.md): after the 14 m example path, sampled
// at driver_rs485a's 4 Hz, at most 3 cm and 0.2 degree.
constexpr double kTolerance4HzM = 0.03, kToleranceHeadingRad = 0.2 * kPi / 180;

TEST(Odometry, ExamplePathAt4Hz) {
  const World room = test::example_room();
  Robot r(test::exact_robot(), room);
  const ScriptedPath path = load_path(test::kConfDir + "/square-path.yaml");
  const OdometryError e = run_path(r, path, 0.01, 0.25);
  std::printf("example path: %.2f m driven, odometry error %.4f m, %.4f deg (4 Hz samples)\n", e.distance_m,
              e.position_m, rad_to_deg(e.heading_rad));
  EXPECT_GT(e.distance_m, 14.0);  // the path was driven, not stopped by a bumper
  EXPECT_EQ(r.sense().pause, 0);
  EXPECT_LT(e.position_m, kTolerance4HzM);
  EXPECT_LT(e.heading_rad, kToleranceHeadingRad);
}

// Two error sources: a command change inside a sample (one arc assumed for
// two) shrinks with the sample period; whole ticks make the per-sample
// Ackermann inversion noisy, which grows with the sample rate. With very fine
// encoders only the first is left, and faster sampling must help.
TEST(Odometry, WithFineEncodersFasterSamplingIsMoreAccurate) {
  const World room = test::example_room();
  const ScriptedPath path = load_path(test::kConfDir + "/square-path.yaml");
  RobotDescription fine = test::exact_robot();
  fine.chassis.ticks_per_rev = 2048.0 * 1024;
  Robot slow(fine, room), fast(fine, room), coarse_fast(test::exact_robot(), room);
  const OdometryError e4 = run_path(slow, path, 0.01, 0.25);
  const OdometryError e50 = run_path(fast, path, 0.01, 0.02);
  const OdometryError coarse50 = run_path(coarse_fast, path, 0.01, 0.02);
  std::printf("fine encoders: %.4f m at 4 Hz, %.4f m at 50 Hz; 2048 ticks/rev at 50 Hz: %.4f m\n",
              e4.position_m, e50.position_m, coarse50.position_m);
  EXPECT_LT(e50.position_m, e4.position_m / 4);
  EXPECT_LT(e50.position_m, 0.005);
}

TEST(Odometry, StraightLineIsExactToOneTick) {
  World open;
  Robot r(test::exact_robot(), open);
  const OdometryError e = run_path(r, ScriptedPath({{0.7, 0, 10}}), 0.01, 0.25);
  EXPECT_NEAR(e.distance_m, 7.0, 1e-9);
  EXPECT_LT(e.position_m, 2 * kPi * 0.125 / 2048);  // one tick of wheel travel
}

TEST(ScriptedPathTest, CommandsFollowTheSegments) {
  const ScriptedPath p({{0.5, 0.1, 2}, {-0.2, 0, 1}});
  EXPECT_DOUBLE_EQ(p.duration(), 3);
  EXPECT_DOUBLE_EQ(p.at(0).speed_mps, 0.5);
  EXPECT_DOUBLE_EQ(p.at(1.99).steering_rad, 0.1);
  EXPECT_DOUBLE_EQ(p.at(2.5).speed_mps, -0.2);
  EXPECT_DOUBLE_EQ(p.at(3.5).speed_mps, 0);  // after the end: stop
}

}  // namespace
}  // namespace advee::robotsim
