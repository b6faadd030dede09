// SPDX-License-Identifier: GPL-2.0
#include <gtest/gtest.h>

#include <cmath>

#include "advee/robotsim/geometry.hpp"
#include "test_util.hpp"

namespace advee::robotsim {
namespace {

TEST(RayCast, WallStraightAhead) {
  const World w = test::example_room();
  // From (2, 2) east: the wall x = 10 is 8 m away.
  EXPECT_NEAR(*w.ray_cast({2, 2}, 0, 20), 8.0, 1e-9);
  // North-east at 45 degrees: the box's west side (x = 4) at (4, 4).
  EXPECT_NEAR(*w.ray_cast({2, 2}, kPi / 4, 20), 2 * std::sqrt(2.0), 1e-9);
  // From (6, 2) north-east: the wall x = 10 at (10, 6), 4 * sqrt(2) m.
  EXPECT_NEAR(*w.ray_cast({6, 2}, kPi / 4, 20), 4 * std::sqrt(2.0), 1e-9);
  // West: x = 0 after 2 m.
  EXPECT_NEAR(*w.ray_cast({2, 2}, kPi, 20), 2.0, 1e-9);
}

TEST(RayCast, BoxAndCircleObstacles) {
  const World w = test::example_room();
  // The box spans x 4.0..5.0, y 3.9..4.7.
  EXPECT_NEAR(*w.ray_cast({1, 4.3}, 0, 20), 3.0, 1e-9);
  EXPECT_NEAR(*w.ray_cast({4.5, 1}, kPi / 2, 20), 2.9, 1e-9);
  // The pillar (8.8, 1.2) r 0.3 from the west along y = 1.2: 8.5 - 6 = 2.5.
  EXPECT_NEAR(*w.ray_cast({6, 1.2}, 0, 20), 2.5, 1e-9);
  // Grazing the pillar off-centre: chord at 0.18 off the centre line,
  // sqrt(0.3^2 - 0.18^2) = 0.24 before the centre.
  EXPECT_NEAR(*w.ray_cast({6, 1.38}, 0, 20), 2.8 - 0.24, 1e-9);
}

TEST(RayCast, BeyondMaxRangeIsNoHit) {
  const World w = test::example_room();
  EXPECT_FALSE(w.ray_cast({2, 2}, 0, 7.9).has_value());
  EXPECT_TRUE(w.ray_cast({2, 2}, 0, 8.0).has_value());
}

TEST(LineOfSight, BoxHidesWhatIsBehindIt) {
  const World w = test::example_room();
  EXPECT_FALSE(w.line_of_sight({1, 4.3}, {9, 4.3}));
  EXPECT_TRUE(w.line_of_sight({1, 2}, {9, 2}));
  // A beacon in a corner is not hidden by the walls it sits next to.
  EXPECT_TRUE(w.line_of_sight({6, 2}, {9.95, 7.95}));
}

TEST(Contacts, RectangleAgainstWallAndPillar) {
  const World w = test::example_room();
  EXPECT_TRUE(w.contacts({{1, 1}, {2, 1}, {2, 2}, {1, 2}}).empty());
  EXPECT_FALSE(w.contacts({{9.5, 1}, {10.5, 1}, {10.5, 2}, {9.5, 2}}).empty());  // crosses x = 10
  EXPECT_FALSE(w.contacts({{8.0, 1.0}, {8.6, 1.0}, {8.6, 1.4}, {8.0, 1.4}}).empty());  // 0.1 into the pillar
  EXPECT_TRUE(w.contacts({{8.0, 1.0}, {8.45, 1.0}, {8.45, 1.4}, {8.0, 1.4}}).empty());  // 0.05 short of it
}

TEST(Angles, WrapAndFrames) {
  EXPECT_NEAR(wrap_angle(3 * kPi / 2), -kPi / 2, 1e-12);
  EXPECT_NEAR(wrap_angle(-kPi), kPi, 1e-12);
  const Pose p{{1, 2}, kPi / 2};
  const Vec2 w = p.to_world({1, 0});
  EXPECT_NEAR(w.x(), 1, 1e-12);
  EXPECT_NEAR(w.y(), 3, 1e-12);
  EXPECT_NEAR((p.to_robot(w) - Vec2(1, 0)).norm(), 0, 1e-12);
}

}  // namespace
}  // namespace advee::robotsim
