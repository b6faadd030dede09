// SPDX-License-Identifier: GPL-2.0
// SIM_DATA_POSE (sim.data_pose_t): the virtual robot's true pose, speed,
// steering and PAUSE line on LCM, the ground truth for tests and the
// diagnostic view. Simulator only: not one of the robot's channels
// (advee/msgs/channels.hpp).
#pragma once

#include <memory>
#include <string>

#include "advee/robotsim/robot.hpp"

namespace lcm {
class LCM;
}

namespace advee::robotsim {

inline constexpr const char* kSimDataPoseChannel = "SIM_DATA_POSE";

class PosePublisher {
 public:
  // `url` empty: the robot's (advee/msgs/bus.hpp); throws std::runtime_error
  // when LCM cannot be set up.
  explicit PosePublisher(const std::string& url);
  // Publishes through `lcm`, which must outlive the publisher (tests: memq://).
  explicit PosePublisher(lcm::LCM& lcm);
  ~PosePublisher();
  PosePublisher(const PosePublisher&) = delete;
  PosePublisher& operator=(const PosePublisher&) = delete;

  void publish(const Robot& robot);

 private:
  std::unique_ptr<lcm::LCM> owned_;
  lcm::LCM* lcm_;
};

}  // namespace advee::robotsim
