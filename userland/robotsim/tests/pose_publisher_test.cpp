// SPDX-License-Identifier: GPL-2.0
// SIM_DATA_POSE carries the robot's true state: pose, speed, steering, the
// PAUSE line and the encoder counts, on LCM's in-process transport.
#include <gtest/gtest.h>

#include <lcm/lcm-cpp.hpp>
#include <optional>

#include "advee/robotsim/pose_publisher.hpp"
#include "sim/data_pose_t.hpp"
#include "test_util.hpp"

namespace advee::robotsim {
namespace {

struct Received {
  std::optional<sim::data_pose_t> last;
};
void on_pose(const lcm::ReceiveBuffer*, const std::string&, const sim::data_pose_t* m, Received* rx) { rx->last = *m; }

TEST(PosePublisher, PublishesTheTrueStateOnSimDataPose) {
  lcm::LCM lcm("memq://");
  ASSERT_TRUE(lcm.good());
  Received rx;
  lcm.subscribeFunction("SIM_DATA_POSE", &on_pose, &rx);
  RobotDescription d = test::exact_robot();
  d.start = Pose{{8.5, 4.0}, 0};  // front bumper 0.6 m from the east wall
  Robot robot(d, test::example_room());
  PosePublisher pub(lcm);
  for (int i = 0; i < 100; ++i) robot.step(0.4, deg_to_rad(10), 0.01);
  pub.publish(robot);
  ASSERT_EQ(lcm.handleTimeout(1000), 1);
  ASSERT_TRUE(rx.last);
  EXPECT_NEAR(rx.last->sim_time_s, 1.0, 1e-9);
  EXPECT_NEAR(rx.last->x_m, robot.pose().position.x(), 1e-12);
  EXPECT_NEAR(rx.last->y_m, robot.pose().position.y(), 1e-12);
  EXPECT_GT(rx.last->y_m, 4.0);  // turning left
  EXPECT_NEAR(rx.last->heading_rad, robot.pose().heading, 1e-12);
  EXPECT_NEAR(rx.last->speed_mps, 0.4, 1e-12);
  EXPECT_NEAR(rx.last->steering_rad, deg_to_rad(10), 1e-12);
  EXPECT_EQ(rx.last->pause_engaged, false);
  EXPECT_GT(rx.last->ticks_left, 900);  // ~0.4 m of 2048 ticks per 0.785 m
  EXPECT_GT(rx.last->ticks_right, rx.last->ticks_left);  // outer wheel in a left turn
  // On into the wall: the bumper engages PAUSE and the speed drops to 0.
  for (int i = 0; i < 200; ++i) robot.step(0.4, 0, 0.01);
  pub.publish(robot);
  ASSERT_EQ(lcm.handleTimeout(1000), 1);
  EXPECT_EQ(rx.last->pause_sources, kPauseFrontBumper);
  EXPECT_TRUE(rx.last->pause_engaged);
  EXPECT_EQ(rx.last->speed_mps, 0);
}

}  // namespace
}  // namespace advee::robotsim
