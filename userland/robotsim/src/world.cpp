// SPDX-License-Identifier: GPL-2.0
#include "advee/robotsim/world.hpp"

#include <cmath>

namespace advee::robotsim {

void World::add_polygon(const std::vector<Vec2>& v) {
  for (std::size_t i = 0; i < v.size(); ++i) segments_.push_back({v[i], v[(i + 1) % v.size()]});
}

void World::add_box(const Vec2& centre, const Vec2& size, double yaw) {
  const Pose frame{centre, yaw};
  const double hx = size.x() / 2, hy = size.y() / 2;
  add_polygon({frame.to_world({hx, hy}), frame.to_world({-hx, hy}), frame.to_world({-hx, -hy}),
               frame.to_world({hx, -hy})});
}

std::optional<double> World::ray_cast(const Vec2& origin, double angle, double max_range) const {
  const Vec2 dir(std::cos(angle), std::sin(angle));
  std::optional<double> best;
  const auto keep = [&](std::optional<double> t) {
    if (t && *t <= max_range && (!best || *t < *best)) best = t;
  };
  for (const auto& s : segments_) keep(ray_segment(origin, dir, s));
  for (const auto& c : circles_) keep(ray_circle(origin, dir, c));
  return best;
}

bool World::line_of_sight(const Vec2& a, const Vec2& b) const {
  const double d = (b - a).norm();
  if (d == 0) return true;
  const Vec2 dir = (b - a) / d;
  // A beacon mounted on a wall must not hide behind that wall: only surfaces
  // clearly before the target block the line.
  const double limit = d - 1e-6;
  for (const auto& s : segments_)
    if (auto t = ray_segment(a, dir, s); t && *t < limit) return false;
  for (const auto& c : circles_)
    if (auto t = ray_circle(a, dir, c); t && *t < limit) return false;
  return true;
}

std::vector<Vec2> World::contacts(const std::vector<Vec2>& outline) const {
  std::vector<Vec2> hits;
  for (const auto& s : segments_) {
    for (std::size_t i = 0; i < outline.size(); ++i)
      if (auto p = segment_intersection({outline[i], outline[(i + 1) % outline.size()]}, s)) hits.push_back(*p);
    for (const Vec2& end : {s.a, s.b})
      if (inside_polygon(outline, end)) hits.push_back(end);
  }
  for (const auto& c : circles_) {
    if (inside_polygon(outline, c.centre)) {
      hits.push_back(c.centre);
      continue;
    }
    for (std::size_t i = 0; i < outline.size(); ++i) {
      const Vec2 p = closest_point({outline[i], outline[(i + 1) % outline.size()]}, c.centre);
      if ((p - c.centre).norm() <= c.radius) hits.push_back(p);
    }
  }
  return hits;
}

}  // namespace advee::robotsim
