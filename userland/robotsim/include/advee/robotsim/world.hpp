// SPDX-License-Identifier: GPL-2.0
// The virtual robot's room: walls and box obstacles (as segments), round
// obstacles, infrared beacons. Loaded from a YAML map file (docs/robotsim.md).
#pragma once

#include <cstdint>
#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

#include "advee/config_error.hpp"
#include "advee/robotsim/geometry.hpp"

namespace advee::robotsim {

// A map or robot file that cannot be used; what() names the file, line and
// field (advee/config_error.hpp: one type for every configuration file).
using advee::ConfigError;

struct Beacon {
  std::uint8_t id;
  Vec2 position;
};

class World {
 public:
  void add_segment(const Segment& s) { segments_.push_back(s); }
  // A closed polygon (the last vertex joins the first).
  void add_polygon(const std::vector<Vec2>& vertices);
  // A rectangle of `size` centred on `centre`, rotated by `yaw` radians.
  void add_box(const Vec2& centre, const Vec2& size, double yaw);
  void add_circle(const Circle& c) { circles_.push_back(c); }
  void add_beacon(const Beacon& b) { beacons_.push_back(b); }

  const std::vector<Segment>& segments() const { return segments_; }
  const std::vector<Circle>& circles() const { return circles_; }
  const std::vector<Beacon>& beacons() const { return beacons_; }

  // Distance to the first surface along the ray, if any within max_range.
  std::optional<double> ray_cast(const Vec2& origin, double angle, double max_range) const;
  // True when nothing stands on the straight line from a to b.
  bool line_of_sight(const Vec2& a, const Vec2& b) const;
  // Points where the closed polygon `outline` touches a surface: segment
  // crossings, surface vertices inside it, the nearest boundary point of a
  // circle that reaches into it. Empty: no contact.
  std::vector<Vec2> contacts(const std::vector<Vec2>& outline) const;

 private:
  std::vector<Segment> segments_;
  std::vector<Circle> circles_;
  std::vector<Beacon> beacons_;
};

// Parses a map (YAML text); `name` prefixes error messages (usually the path).
World parse_world(const std::string& yaml_text, const std::string& name);
World load_world(const std::string& path);

}  // namespace advee::robotsim
