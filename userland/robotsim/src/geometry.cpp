// SPDX-License-Identifier: GPL-2.0
#include "advee/robotsim/geometry.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>

namespace advee::robotsim {

namespace {
double cross(const Vec2& a, const Vec2& b) { return a.x() * b.y() - a.y() * b.x(); }
constexpr double kEps = 1e-12;
}  // namespace

Vec2 Pose::to_world(const Vec2& p) const {
  const double c = std::cos(heading), s = std::sin(heading);
  return position + Vec2(c * p.x() - s * p.y(), s * p.x() + c * p.y());
}

Vec2 Pose::to_robot(const Vec2& w) const {
  const Vec2 d = w - position;
  const double c = std::cos(heading), s = std::sin(heading);
  return {c * d.x() + s * d.y(), -s * d.x() + c * d.y()};
}

double wrap_angle(double a) {
  a = std::remainder(a, 2 * std::numbers::pi);  // [-pi, pi]
  return a <= -std::numbers::pi ? a + 2 * std::numbers::pi : a;
}

std::optional<double> ray_segment(const Vec2& o, const Vec2& d, const Segment& s) {
  const Vec2 e = s.b - s.a;
  const double denom = cross(d, e);
  if (std::abs(denom) < kEps) return std::nullopt;  // parallel: a grazing ray sees no surface
  const Vec2 ao = s.a - o;
  const double t = cross(ao, e) / denom;  // along the ray
  const double u = cross(ao, d) / denom;  // along the segment
  if (t < 0 || u < -1e-9 || u > 1 + 1e-9) return std::nullopt;
  return t;
}

std::optional<double> ray_circle(const Vec2& o, const Vec2& d, const Circle& c) {
  const Vec2 oc = o - c.centre;
  const double b = oc.dot(d);
  const double q = oc.squaredNorm() - c.radius * c.radius;
  const double disc = b * b - q;
  if (disc < 0) return std::nullopt;
  const double root = std::sqrt(disc);
  const double t0 = -b - root, t1 = -b + root;
  if (t0 >= 0) return t0;
  if (t1 >= 0) return 0.0;  // the origin is inside the circle
  return std::nullopt;
}

std::optional<Vec2> segment_intersection(const Segment& p, const Segment& q) {
  const Vec2 r = p.b - p.a, s = q.b - q.a;
  const double denom = cross(r, s);
  const Vec2 qp = q.a - p.a;
  if (std::abs(denom) < kEps) {
    // Parallel: collinear overlap touches at an endpoint lying on the other segment.
    if (std::abs(cross(qp, r)) > 1e-9) return std::nullopt;
    const auto on = [](const Segment& seg, const Vec2& pt) { return (closest_point(seg, pt) - pt).norm() < 1e-9; };
    if (on(p, q.a)) return q.a;
    if (on(p, q.b)) return q.b;
    if (on(q, p.a)) return p.a;
    if (on(q, p.b)) return p.b;
    return std::nullopt;
  }
  const double t = cross(qp, s) / denom, u = cross(qp, r) / denom;
  if (t < -1e-9 || t > 1 + 1e-9 || u < -1e-9 || u > 1 + 1e-9) return std::nullopt;
  return Vec2(p.a + t * r);
}

Vec2 closest_point(const Segment& s, const Vec2& p) {
  const Vec2 e = s.b - s.a;
  const double len2 = e.squaredNorm();
  if (len2 < kEps) return s.a;
  const double t = std::clamp((p - s.a).dot(e) / len2, 0.0, 1.0);
  return s.a + t * e;
}

bool inside_polygon(const std::vector<Vec2>& poly, const Vec2& p) {
  bool in = false;
  for (std::size_t i = 0, j = poly.size() - 1; i < poly.size(); j = i++) {
    const Vec2 &a = poly[i], &b = poly[j];
    if ((a.y() > p.y()) != (b.y() > p.y()) &&
        p.x() < (b.x() - a.x()) * (p.y() - a.y()) / (b.y() - a.y()) + a.x())
      in = !in;
  }
  return in;
}

}  // namespace advee::robotsim
