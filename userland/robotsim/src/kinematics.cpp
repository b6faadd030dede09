// SPDX-License-Identifier: GPL-2.0
#include "advee/robotsim/kinematics.hpp"

#include <algorithm>
#include <cmath>

namespace advee::robotsim {

Pose integrate_arc(const Pose& p, double v, double w, double dt) {
  const double dth = w * dt;
  const double ds = v * dt;
  Vec2 local;
  if (std::abs(dth) < 1e-9) {
    local = {ds, 0};  // second-order term below double precision
  } else {
    const double r = ds / dth;
    local = {r * std::sin(dth), r * (1 - std::cos(dth))};
  }
  return {p.to_world(local), wrap_angle(p.heading + dth)};
}

double yaw_rate(double v, double steering_rad, double wheelbase_m) {
  return v * std::tan(steering_rad) / wheelbase_m;
}

std::array<double, 2> front_wheel_distances(double v, double w, double l, double t, double dt) {
  const double sign = v < 0 ? -1.0 : 1.0;
  const auto rolled = [&](double y) { return sign * std::hypot(v - w * y, w * l) * dt; };
  return {rolled(t / 2), rolled(-t / 2)};
}

Motion motion_from_front_wheels(double left, double right, double l, double t) {
  // With ds the rear-axle distance and dth the heading change over a constant
  // arc: left^2 + right^2 = 2 ds^2 + 2 K dth^2 (K = l^2 + t^2/4) and
  // right^2 - left^2 = 2 t ds dth; ds^2 is the larger root of x^2 - S x + K P^2.
  const double k = l * l + t * t / 4;
  const double s = (left * left + right * right) / 2;
  const double p = (right * right - left * left) / (2 * t);
  const double disc = std::max(0.0, s * s - 4 * k * p * p);
  const double ds_abs = std::sqrt((s + std::sqrt(disc)) / 2);
  if (ds_abs == 0) return {};
  const double ds = (left + right) < 0 ? -ds_abs : ds_abs;
  return {ds, p / ds};
}

}  // namespace advee::robotsim
