// SPDX-License-Identifier: GPL-2.0
// Shared fixtures of the robotsim tests: the example room and an exact
// (noise-free) robot.
#pragma once

#include <string>

#include "advee/robotsim/robot.hpp"
#include "advee/robotsim/world.hpp"

namespace advee::robotsim::test {

inline const std::string kConfDir = ADVEE_ROBOTSIM_CONF_DIR;

// 10 m x 8 m room, box 1.0 x 0.8 at (4.5, 4.3), pillar r 0.3 at (8.8, 1.2).
inline World example_room() { return load_world(kConfDir + "/room.yaml"); }

inline RobotDescription exact_robot() {
  RobotDescription d = load_robot(kConfDir + "/robot.yaml");
  d.srf.noise_m = 0;
  d.ir.noise_m = 0;
  d.scanner.noise_deg = 0;
  return d;
}

}  // namespace advee::robotsim::test
