// SPDX-License-Identifier: GPL-2.0
// The map file (docs/robotsim.md): walls (closed polygons or segments),
// obstacles (box or circle) and beacons.
#include <set>

#include "advee/robotsim/world.hpp"
#include "yaml_util.hpp"

namespace advee::robotsim {

namespace {

using yaml::Ctx;

std::string at(const std::string& list, std::size_t i) { return list + "[" + std::to_string(i) + "]"; }

void read_walls(const Ctx& c, const YAML::Node& walls, World& w) {
  if (!walls.IsSequence()) c.fail(walls, "walls", "expected a list");
  for (std::size_t i = 0; i < walls.size(); ++i) {
    const YAML::Node& n = walls[i];
    const std::string f = at("walls", i);
    if (n.IsMap() && n["polygon"]) {
      const YAML::Node& p = n["polygon"];
      if (!p.IsSequence() || p.size() < 3) c.fail(p, f + ".polygon", "expected at least 3 [x, y] vertices");
      std::vector<Vec2> v;
      for (std::size_t k = 0; k < p.size(); ++k) v.push_back(yaml::point(c, p[k], at(f + ".polygon", k)));
      w.add_polygon(v);
    } else if (n.IsMap() && n["segment"]) {
      const YAML::Node& s = n["segment"];
      if (!s.IsSequence() || s.size() != 2) c.fail(s, f + ".segment", "expected [[x, y], [x, y]]");
      const Vec2 a = yaml::point(c, s[0], f + ".segment[0]"), b = yaml::point(c, s[1], f + ".segment[1]");
      if ((a - b).norm() == 0) c.fail(s, f + ".segment", "the two ends coincide");
      w.add_segment({a, b});
    } else {
      c.fail(n, f, "expected 'polygon: [[x, y], ...]' or 'segment: [[x, y], [x, y]]'");
    }
  }
}

void read_obstacles(const Ctx& c, const YAML::Node& list, World& w) {
  if (!list.IsSequence()) c.fail(list, "obstacles", "expected a list");
  for (std::size_t i = 0; i < list.size(); ++i) {
    const YAML::Node& n = list[i];
    const std::string f = at("obstacles", i);
    const std::string type = yaml::need(c, n, "type", f + ".type").as<std::string>();
    const Vec2 centre = yaml::point(c, yaml::need(c, n, "centre", f + ".centre"), f + ".centre");
    if (type == "box") {
      const Vec2 size = yaml::point(c, yaml::need(c, n, "size", f + ".size"), f + ".size");
      if (!(size.x() > 0 && size.y() > 0)) c.fail(n["size"], f + ".size", "both sides must be > 0");
      const double yaw = yaml::number_or(c, n, "yaw_deg", f + ".yaw_deg", 0.0);
      w.add_box(centre, size, deg_to_rad(yaw));
    } else if (type == "circle") {
      const double r = yaml::number(c, yaml::need(c, n, "radius", f + ".radius"), f + ".radius");
      if (!(r > 0)) c.fail(n["radius"], f + ".radius", "must be > 0");
      w.add_circle({centre, r});
    } else {
      c.fail(n["type"], f + ".type", "'" + type + "': expected box or circle");
    }
  }
}

void read_beacons(const Ctx& c, const YAML::Node& list, World& w) {
  if (!list.IsSequence()) c.fail(list, "beacons", "expected a list");
  std::set<long> ids;
  for (std::size_t i = 0; i < list.size(); ++i) {
    const YAML::Node& n = list[i];
    const std::string f = at("beacons", i);
    const long id = yaml::integer(c, yaml::need(c, n, "id", f + ".id"), f + ".id", 0, 255);
    if (!ids.insert(id).second) c.fail(n["id"], f + ".id", "duplicate beacon id " + std::to_string(id));
    w.add_beacon({static_cast<std::uint8_t>(id),
                  yaml::point(c, yaml::need(c, n, "position", f + ".position"), f + ".position")});
  }
}

}  // namespace

World parse_world(const std::string& text, const std::string& name) {
  const Ctx c{name};
  const YAML::Node doc = yaml::parse(text, name);
  for (const auto& kv : doc) {
    const std::string key = kv.first.as<std::string>();
    if (key != "walls" && key != "obstacles" && key != "beacons")
      c.fail(kv.first, key, "unknown field (expected walls, obstacles, beacons)");
  }
  World w;
  read_walls(c, yaml::need(c, doc, "walls", "walls"), w);
  if (doc["obstacles"]) read_obstacles(c, doc["obstacles"], w);
  if (doc["beacons"]) read_beacons(c, doc["beacons"], w);
  return w;
}

World load_world(const std::string& path) { return parse_world(yaml::read_file(path), path); }

}  // namespace advee::robotsim
