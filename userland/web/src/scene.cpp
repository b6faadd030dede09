// SPDX-License-Identifier: GPL-2.0
#include "advee/web/scene.hpp"

#include <exception>

namespace advee::web {

using nlohmann::json;

json robot_json(const robotsim::RobotDescription& robot) {
  const auto& c = robot.chassis;
  json srfs = json::array();
  for (const auto& s : robot.srf.sensors)
    srfs.push_back({{"id", s.board * 8 + s.index},
                    {"x", s.position.x()},
                    {"y", s.position.y()},
                    {"heading_rad", robotsim::deg_to_rad(s.heading_deg)}});
  return {
      {"outline", {{"front_m", c.front_m}, {"rear_m", c.rear_m}, {"half_width_m", c.half_width_m}}},
      {"wheelbase_m", c.wheelbase_m},
      {"track_m", c.track_m},
      {"wheel_radius_m", c.wheel_radius_m},
      {"start",
       {{"x", robot.start.position.x()}, {"y", robot.start.position.y()},
        {"heading_rad", robot.start.heading}}},
      {"srfs", srfs},
      {"srf_max_m", robot.srf.max_m},
      {"scanner", {{"x", robot.scanner.position.x()}, {"y", robot.scanner.position.y()}}},
  };
}

json world_json(const robotsim::World& world) {
  json segments = json::array(), circles = json::array(), beacons = json::array();
  for (const auto& s : world.segments())
    segments.push_back({s.a.x(), s.a.y(), s.b.x(), s.b.y()});
  for (const auto& c : world.circles()) circles.push_back({c.centre.x(), c.centre.y(), c.radius});
  for (const auto& b : world.beacons())
    beacons.push_back({{"id", b.id}, {"x", b.position.x()}, {"y", b.position.y()}});
  return {{"segments", segments}, {"circles", circles}, {"beacons", beacons}};
}

json load_scene(const std::string& robot_file, const std::string& map_file) {
  json scene = json::object();
  json errors = json::array();
  if (!robot_file.empty()) {
    try {
      scene["robot"] = robot_json(robotsim::load_robot(robot_file));
    } catch (const std::exception& e) {
      errors.push_back(e.what());
    }
  }
  if (!map_file.empty()) {
    try {
      scene["world"] = world_json(robotsim::load_world(map_file));
    } catch (const std::exception& e) {
      errors.push_back(e.what());
    }
  }
  if (!errors.empty()) scene["errors"] = errors;
  return scene;
}

}  // namespace advee::web
