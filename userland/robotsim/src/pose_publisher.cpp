// SPDX-License-Identifier: GPL-2.0
#include "advee/robotsim/pose_publisher.hpp"

#include <chrono>
#include <cmath>
#include <lcm/lcm-cpp.hpp>
#include <stdexcept>

#include "advee/msgs/bus.hpp"
#include "sim/data_pose_t.hpp"

namespace advee::robotsim {

PosePublisher::PosePublisher(const std::string& url)
    : owned_(msgs::open_bus(msgs::bus_url(url))), lcm_(owned_.get()) {}

PosePublisher::PosePublisher(lcm::LCM& lcm) : lcm_(&lcm) {}

PosePublisher::~PosePublisher() = default;

void PosePublisher::publish(const Robot& robot) {
  sim::data_pose_t m{};
  m.utime = std::chrono::duration_cast<std::chrono::microseconds>(
                std::chrono::system_clock::now().time_since_epoch()).count();
  m.sim_time_s = robot.time();
  m.x_m = robot.pose().position.x();
  m.y_m = robot.pose().position.y();
  m.heading_rad = std::remainder(robot.pose().heading, 2 * kPi);
  m.speed_mps = robot.speed();
  m.steering_rad = robot.steering();
  m.pause_sources = static_cast<std::int8_t>(robot.pause_sources());
  m.pause_engaged = robot.pause_sources() != 0;
  m.ticks_left = static_cast<std::int64_t>(std::floor(robot.exact_ticks()[0]));
  m.ticks_right = static_cast<std::int64_t>(std::floor(robot.exact_ticks()[1]));
  if (lcm_->publish(kSimDataPoseChannel, &m) != 0) throw std::runtime_error("LCM: cannot publish SIM_DATA_POSE");
}

}  // namespace advee::robotsim
