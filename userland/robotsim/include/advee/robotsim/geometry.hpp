// SPDX-License-Identifier: GPL-2.0
// Plane geometry of the virtual robot's world: poses, segments, circles, ray
// casts and contact tests. World frame: metres, x east, y north, angles
// counter-clockwise from x in radians.
#pragma once

#include <Eigen/Core>
#include <optional>
#include <vector>

namespace advee::robotsim {

using Vec2 = Eigen::Vector2d;

constexpr double kPi = 3.14159265358979323846;
constexpr double deg_to_rad(double d) { return d * kPi / 180; }
constexpr double rad_to_deg(double r) { return r * 180 / kPi; }

struct Pose {
  Vec2 position = Vec2::Zero();  // middle of the rear axle
  double heading = 0;            // radians, counter-clockwise from world x

  // A point given in the robot frame (x forward, y left) in world coordinates.
  Vec2 to_world(const Vec2& robot_point) const;
  // A direction given in the robot frame (angle from robot x) as a world angle.
  double world_angle(double robot_angle) const { return heading + robot_angle; }
  // A world point in the robot frame.
  Vec2 to_robot(const Vec2& world_point) const;
};

struct Segment {
  Vec2 a, b;
};

struct Circle {
  Vec2 centre;
  double radius;
};

// Wraps an angle to (-pi, pi].
double wrap_angle(double a);

// Distance along the ray (origin, unit direction) to its first hit, or nullopt.
std::optional<double> ray_segment(const Vec2& origin, const Vec2& dir, const Segment& s);
std::optional<double> ray_circle(const Vec2& origin, const Vec2& dir, const Circle& c);

// Intersection point of two segments (touching counts), or nullopt.
std::optional<Vec2> segment_intersection(const Segment& p, const Segment& q);
// Closest point of a segment to a point.
Vec2 closest_point(const Segment& s, const Vec2& p);
// Point inside a simple polygon (vertices in order, either orientation).
bool inside_polygon(const std::vector<Vec2>& polygon, const Vec2& p);

}  // namespace advee::robotsim
