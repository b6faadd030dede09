// SPDX-License-Identifier: GPL-2.0
#include <gtest/gtest.h>

#include <cmath>

#include "advee/robotsim/robot.hpp"
#include "test_util.hpp"

namespace advee::robotsim {
namespace {

std::optional<BeaconReading> beacon(const SensorFrame& f, int id) {
  for (const auto& b : f.beacons)
    if (b.id == id) return b;
  return std::nullopt;
}

RobotDescription at(double x, double y, double heading_deg) {
  RobotDescription d = test::exact_robot();
  d.start = {{x, y}, deg_to_rad(heading_deg)};
  d.scanner.position = Vec2::Zero();  // scanner on the reference point: hand geometry
  return d;
}

TEST(Beacons, BearingsCounterClockwiseFromHeading) {
  World w;
  w.add_beacon({1, {5, 6}});   // left of a robot at (5, 4) heading east
  w.add_beacon({2, {5, 2}});   // right
  w.add_beacon({3, {3, 4}});   // behind
  w.add_beacon({4, {7, 6}});   // 45 degrees left
  Robot r(at(5, 4, 0), w);
  const SensorFrame f = r.sense();
  EXPECT_EQ(beacon(f, 1)->bearing_cdeg, 9000);
  EXPECT_EQ(beacon(f, 2)->bearing_cdeg, 27000);
  EXPECT_EQ(beacon(f, 3)->bearing_cdeg, 18000);
  EXPECT_EQ(beacon(f, 4)->bearing_cdeg, 4500);
  // Heading north: (7, 6) is 45 degrees right, (3, 4) straight left.
  Robot north(at(5, 4, 90), w);
  EXPECT_EQ(beacon(north.sense(), 4)->bearing_cdeg, 31500);
  EXPECT_EQ(beacon(north.sense(), 3)->bearing_cdeg, 9000);
}

TEST(Beacons, BearingWrapsAt360Degrees) {
  EXPECT_EQ(bearing_to_cdeg(0), 0);
  EXPECT_EQ(bearing_to_cdeg(2 * kPi), 0);
  EXPECT_EQ(bearing_to_cdeg(-deg_to_rad(0.01)), 35999);
  EXPECT_EQ(bearing_to_cdeg(-deg_to_rad(0.001)), 0);  // rounds to 360.00 = 0
  EXPECT_EQ(bearing_to_cdeg(deg_to_rad(359.994)), 35999);
  EXPECT_EQ(bearing_to_cdeg(deg_to_rad(-90)), 27000);
  EXPECT_EQ(bearing_to_cdeg(deg_to_rad(450)), 9000);
  // A beacon just right of straight ahead reads just under 360 degrees.
  World w;
  w.add_beacon({7, {9, 3.999}});
  Robot r(at(5, 4, 0), w);
  const auto b = beacon(r.sense(), 7);
  ASSERT_TRUE(b);
  EXPECT_EQ(b->bearing_cdeg, 35999);
}

TEST(Beacons, HiddenOrTooFarBeaconsAreNotReported) {
  const World room = test::example_room();
  // From (1.5, 4.3) the box (x 4..5) hides nothing in the corners; a beacon
  // placed behind the box is hidden.
  World w = room;
  w.add_beacon({9, {8, 4.3}});
  Robot r(at(1.5, 4.3, 0), w);
  const SensorFrame f = r.sense();
  EXPECT_FALSE(beacon(f, 9));
  EXPECT_TRUE(beacon(f, 1));
  EXPECT_TRUE(beacon(f, 4));
  RobotDescription shortsighted = at(1.5, 4.3, 0);
  shortsighted.scanner.max_range_m = 5;
  Robot r2(shortsighted, room);
  const SensorFrame f2 = r2.sense();
  EXPECT_TRUE(beacon(f2, 1));   // 4.6 m
  EXPECT_FALSE(beacon(f2, 2));  // 9.7 m
  EXPECT_GT(beacon(f, 1)->quality, beacon(f, 2)->quality);  // nearer, better
}

TEST(Beacons, NoiseHasTheConfiguredSpread) {
  World w;
  w.add_beacon({1, {5, 6}});
  RobotDescription d = at(5, 4, 0);
  d.scanner.noise_deg = 0.5;
  Robot r(d, w, 42);
  double sum = 0, sum2 = 0;
  const int n = 2000;
  for (int i = 0; i < n; ++i) {
    const double e = beacon(r.sense(), 1)->bearing_cdeg / 100.0 - 90.0;
    sum += e;
    sum2 += e * e;
  }
  const double mean = sum / n, sd = std::sqrt(sum2 / n - mean * mean);
  EXPECT_NEAR(mean, 0, 0.05);
  EXPECT_NEAR(sd, 0.5, 0.05);
}

TEST(Ranges, UltrasonicAndIrFollowTheGeometry) {
  RobotDescription d = at(5, 2, 0);
  d.srf.beam_half_angle_deg = 0;
  d.srf.sensors = {{0, 0, {0.88, 0.08}, 0},     // ahead: wall x = 10 at 10 - 5.88
                   {0, 1, {0.60, 0.28}, 90},    // left: wall y = 8 at 5.72 (east of the box)
                   {1, 0, {-0.22, 0}, 180},     // behind: x = 0 at 4.78 -> within 6 m
                   {1, 1, {0.05, -0.28}, -90}};  // right: wall y = 0 at 1.72
  Robot r(d, test::example_room());
  const SensorFrame f = r.sense();
  ASSERT_EQ(f.srf_m.size(), 4u);
  EXPECT_NEAR(*f.srf_m[0], 4.12, 1e-9);
  EXPECT_NEAR(*f.srf_m[1], 5.72, 1e-9);
  EXPECT_NEAR(*f.srf_m[2], 4.78, 1e-9);
  EXPECT_NEAR(*f.srf_m[3], 1.72, 1e-9);
  // Farther than the SRF-08's 6 m: no echo.
  RobotDescription d2 = d;
  d2.start = {{2, 2}, 0};
  Robot r2(d2, test::example_room());
  EXPECT_FALSE(r2.sense().srf_m[0].has_value());  // 7.12 m
  // The IR sensors see the flat floor at their mounting distance.
  for (const auto& ir : f.ir_m) EXPECT_NEAR(*ir, 0.12, 1e-12);
  EXPECT_EQ(f.pause, 0);
}

TEST(Ranges, ConeSeesTheNearestSurface) {
  // A sensor aimed 30 degrees north of east sees the wall x = 10 obliquely;
  // a 30 degree half-cone also covers the perpendicular, shorter, echo.
  RobotDescription d = at(8, 2, 90);
  d.srf.sensors = {{0, 0, {0, 0}, -60}};  // 30 degrees above east
  d.srf.beam_half_angle_deg = 0;
  Robot narrow(d, test::example_room());
  d.srf.beam_half_angle_deg = 30;         // the cone reaches east: wall x = 10 at 2 m
  Robot wide(d, test::example_room());
  EXPECT_NEAR(*narrow.sense().srf_m[0], 2 / std::cos(deg_to_rad(30)), 1e-9);
  EXPECT_NEAR(*wide.sense().srf_m[0], 2.0, 1e-9);
}

TEST(Bumpers, WallContactStopsTheRobotAndRaisesFrontPause) {
  // Heading east, front bumper 0.9 m ahead of the rear axle: 0.2 m from x = 10.
  Robot r(at(8.9, 4, 0), test::example_room());
  EXPECT_EQ(r.sense().pause, 0);
  for (int i = 0; i < 100; ++i) r.step(0.5, 0, 0.01);  // would drive 0.5 m
  const SensorFrame f = r.sense();
  EXPECT_EQ(f.pause, kPauseFrontBumper);
  EXPECT_GT(f.pose.position.x(), 9.09);  // got to within one step of the wall
  EXPECT_LE(f.pose.position.x(), 9.1);
  EXPECT_EQ(f.speed_mps, 0);
  const auto ticks = r.exact_ticks();
  r.step(0.5, 0, 0.01);
  EXPECT_EQ(r.exact_ticks(), ticks);  // blocked: the wheels do not turn
  // Backing away frees the bumper; the motor has power again one step later
  // (PAUSE cut it while the bumper was pressed).
  r.step(-0.2, 0, 0.1);
  EXPECT_EQ(r.sense().pause, 0);
  EXPECT_EQ(r.exact_ticks(), ticks);
  r.step(-0.2, 0, 0.1);
  EXPECT_LT(r.exact_ticks()[0], ticks[0]);
}

TEST(Bumpers, ReversingIntoThePillarRaisesRearPause) {
  // Heading north with the rear bumper (0.25 m behind the axle) 0.1 m above
  // the pillar's top (y = 1.5).
  Robot r(at(8.8, 1.85, 90), test::example_room());
  EXPECT_EQ(r.sense().pause, 0);
  for (int i = 0; i < 100; ++i) r.step(-0.3, 0, 0.01);
  EXPECT_EQ(r.sense().pause, kPauseRearBumper);
}

TEST(Proximity, CloseRangeRaisesPauseWhenConfigured) {
  RobotDescription d = at(8.5, 4, 0);  // front sensors ~0.6 m from the wall
  d.srf.proximity_pause_m = 0.8;
  Robot r(d, test::example_room());
  EXPECT_TRUE(r.sense().pause & kPauseProximity);
  d.srf.proximity_pause_m = 0.3;
  Robot r2(d, test::example_room());
  EXPECT_FALSE(r2.sense().pause & kPauseProximity);
}

TEST(Thermal, PropulsionLoadWarmsTemp1FirstOrder) {
  World open;
  RobotDescription d = test::exact_robot();  // temp1: propulsion, 25 + 35 * load, tau 120 s
  Robot r(d, open);
  EXPECT_NEAR(r.sense().temperature_c[0], 25, 1e-12);
  for (int i = 0; i < 1200; ++i) r.step(1.5, 0, 0.1);  // one time constant at full speed
  const SensorFrame f = r.sense();
  EXPECT_NEAR(f.temperature_c[0], 25 + 35 * (1 - std::exp(-1.0)), 1e-6);
  EXPECT_NEAR(f.temperature_c[1], 25, 1e-12);  // steering straight: no load
  // Standing still, it cools back toward ambient.
  for (int i = 0; i < 1200; ++i) r.step(0, 0, 0.1);
  EXPECT_LT(r.sense().temperature_c[0], f.temperature_c[0] - 10);
}

}  // namespace
}  // namespace advee::robotsim
