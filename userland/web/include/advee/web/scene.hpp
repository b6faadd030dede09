// SPDX-License-Identifier: GPL-2.0
// What the page draws besides the messages: the robot's outline, where its
// range finders and beacon scanner sit, and the room (walls, obstacles,
// beacons). Served as /scene.json from advee-robot-sim's robot and map files, so
// the plot and the virtual robot share one description.
#pragma once

#include <nlohmann/json.hpp>
#include <string>

#include "advee/robotsim/robot.hpp"
#include "advee/robotsim/world.hpp"

namespace advee::web {

// {"robot": {"outline": {front_m, rear_m, half_width_m}, wheelbase_m, track_m,
//   "start": {x, y, heading_rad}, "srfs": [{id, x, y, heading_rad}],
//   "scanner": {x, y}},
//  "world": {"segments": [[x1,y1,x2,y2]], "circles": [[x,y,r]],
//   "beacons": [{id, x, y}]}}
// SRF ids are board * 8 + index (front board 0..7, rear 8..15), the ids of
// driver_rs485a.yaml that LL_DATA_SRFS carries.
nlohmann::json robot_json(const robotsim::RobotDescription& robot);
nlohmann::json world_json(const robotsim::World& world);

// Loads the files; a file that is missing or wrong leaves its part out and
// adds {"errors": [...]} with the loader's message, so that the page still
// shows the live data.
nlohmann::json load_scene(const std::string& robot_file, const std::string& map_file);

}  // namespace advee::web
