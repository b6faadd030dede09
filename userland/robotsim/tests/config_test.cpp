// SPDX-License-Identifier: GPL-2.0
#include <gtest/gtest.h>

#include "advee/robotsim/robot.hpp"
#include "advee/robotsim/scripted_path.hpp"
#include "test_util.hpp"

namespace advee::robotsim {
namespace {

std::string map_error(const std::string& text) {
  try {
    parse_world(text, "m.yaml");
  } catch (const ConfigError& e) {
    return e.what();
  }
  return "no error";
}

std::string robot_error(const std::string& text) {
  try {
    parse_robot(text, "r.yaml");
  } catch (const ConfigError& e) {
    return e.what();
  }
  return "no error";
}

const std::string kSensors =
    "srf:\n  sensors:\n    - {board: front, index: 0, x: 0.8, y: 0, heading_deg: 0}\n"
    "ir:\n  sensors:\n    - {board: rear, index: 1, x: -0.2, y: 0}\n";

TEST(ExampleFiles, Load) {
  const World w = test::example_room();
  EXPECT_EQ(w.segments().size(), 8u);  // 4 walls + 4 box sides
  EXPECT_EQ(w.circles().size(), 1u);
  EXPECT_EQ(w.beacons().size(), 4u);
  const RobotDescription d = load_robot(test::kConfDir + "/robot.yaml");
  EXPECT_EQ(d.srf.sensors.size(), 16u);
  EXPECT_EQ(d.ir.sensors.size(), 4u);
  EXPECT_EQ(d.thermal.size(), 2u);
  EXPECT_DOUBLE_EQ(d.chassis.ticks_per_rev, 2048);
  EXPECT_EQ(load_path(test::kConfDir + "/square-path.yaml").segments().size(), 6u);
}

TEST(MapErrors, NameFileLineAndField) {
  EXPECT_EQ(map_error("obstacles: []\n"), "m.yaml:1: walls: missing");
  EXPECT_EQ(map_error("walls:\n  - polygon: [[0, 0], [1, 0]]\n"),
            "m.yaml:2: walls[0].polygon: expected at least 3 [x, y] vertices");
  EXPECT_EQ(map_error("walls: []\nobstacles:\n  - {type: circle, centre: [1, 1], radius: -2}\n"),
            "m.yaml:3: obstacles[0].radius: must be > 0");
  EXPECT_EQ(map_error("walls: []\nobstacles:\n  - {type: cone, centre: [1, 1]}\n"),
            "m.yaml:3: obstacles[0].type: 'cone': expected box or circle");
  EXPECT_EQ(map_error("walls: []\nbeacons:\n  - {id: 1, position: [0, 0]}\n  - {id: 1, position: [1, 0]}\n"),
            "m.yaml:4: beacons[1].id: duplicate beacon id 1");
  EXPECT_EQ(map_error("walls:\n  - segment: [[0, 0], [1, zero]]\n"),
            "m.yaml:2: walls[0].segment[1][1]: 'zero' is not a number");
  EXPECT_EQ(map_error("walls: []\nbeacon: []\n"), "m.yaml:2: beacon: unknown field (expected walls, obstacles, beacons)");
  EXPECT_EQ(map_error("walls: [\n"), "m.yaml:2: YAML syntax: end of sequence flow not found");
}

TEST(MapErrors, MissingFile) {
  EXPECT_THROW(load_world("/nonexistent/room.yaml"), ConfigError);
}

TEST(RobotErrors, NameFileLineAndField) {
  EXPECT_EQ(robot_error(kSensors), "no error");
  EXPECT_EQ(robot_error("ir:\n  sensors: []\n"), "r.yaml:1: srf: missing");
  EXPECT_EQ(robot_error("chassis:\n  wheelbase_m: 0\n" + kSensors), "r.yaml:2: chassis.wheelbase_m: must be > 0");
  EXPECT_EQ(robot_error("chassis:\n  max_steering_deg: 50\n" + kSensors),
            "r.yaml:2: chassis.max_steering_deg: must be below 42.682076 for this wheelbase and track");
  EXPECT_EQ(robot_error("srf:\n  sensors:\n    - {board: middle, index: 0, x: 0, y: 0, heading_deg: 0}\n"),
            "r.yaml:3: srf.sensors[0].board: expected front or rear");
  EXPECT_EQ(robot_error("srf:\n  sensors:\n    - {board: front, index: 8, x: 0, y: 0, heading_deg: 0}\n"),
            "r.yaml:3: srf.sensors[0].index: must be an integer in 0..7");
  EXPECT_EQ(robot_error("srf:\n  sensors:\n    - {board: front, index: 0, x: 0, y: 0}\n"),
            "r.yaml:3: srf.sensors[0].heading_deg: missing");
  EXPECT_EQ(robot_error(kSensors + "thermal:\n  - {load: brakes, tau_s: 3}\n"),
            "r.yaml:8: thermal[0].load: expected propulsion or steering");
  EXPECT_EQ(robot_error(kSensors + "wheels: 4\n"), "r.yaml:7: robot.wheels: unknown field");
}

TEST(PathErrors, DurationMustBePositive) {
  try {
    parse_path("path:\n  - {speed_mps: 0.5, duration_s: 0}\n", "p.yaml");
    FAIL() << "accepted a zero duration";
  } catch (const ConfigError& e) {
    EXPECT_STREQ(e.what(), "p.yaml:2: path[0].duration_s: must be > 0");
  }
}

}  // namespace
}  // namespace advee::robotsim
