// SPDX-License-Identifier: GPL-2.0
#include "advee/driver_rs485/odometry.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <stdexcept>

namespace advee::driver_rs485 {

AckermannOdometry::AckermannOdometry(const ChassisGeometry& g) : g_(g) {
  if (!(g.wheel_radius_m > 0) || !(g.ticks_per_rev > 0) || !(g.track_m > 0) ||
      (g.encoders_on_front && !(g.wheelbase_m > 0)))
    throw std::invalid_argument("chassis geometry: radius, ticks per revolution, track and wheelbase must be > 0");
  metres_per_tick_ = 2 * std::numbers::pi * g.wheel_radius_m / g.ticks_per_rev;
  const double x = g.encoders_on_front ? g.wheelbase_m : 0.0;
  left_pos_ = {x, g.track_m / 2};
  right_pos_ = {x, -g.track_m / 2};
}

BodySpeed AckermannOdometry::from_ticks(double ticks_left, double ticks_right, double interval_s) const {
  if (!(interval_s > 0)) throw std::invalid_argument("odometry interval must be > 0");
  return from_wheel_speeds(ticks_left * metres_per_tick_ / interval_s,
                           ticks_right * metres_per_tick_ / interval_s);
}

Eigen::Vector2d AckermannOdometry::wheel_speeds(const BodySpeed& s) const {
  // Velocity of a point p of the rigid body: (v, 0) + w * (-p.y, p.x).
  const Eigen::Vector2d body(s.speed_mps, 0.0);
  const auto point_velocity = [&](const Eigen::Vector2d& p) {
    return Eigen::Vector2d(body + s.yaw_rate_radps * Eigen::Vector2d(-p.y(), p.x()));
  };
  const Eigen::Vector2d vl = point_velocity(left_pos_), vr = point_velocity(right_pos_);
  if (!g_.encoders_on_front) return {vl.x(), vr.x()};  // rear wheels roll along x
  // A steered wheel rolls along its own velocity: the sign is the direction of travel.
  const double sign = s.speed_mps < 0 ? -1.0 : 1.0;
  return {sign * vl.norm(), sign * vr.norm()};
}

BodySpeed AckermannOdometry::from_wheel_speeds(double left_mps, double right_mps) const {
  const double t = g_.track_m;
  if (!g_.encoders_on_front) return {(left_mps + right_mps) / 2, (right_mps - left_mps) / t};
  // v^2 + K w^2 = S and v w = P (see the header): v^2 is the larger root of
  // x^2 - S x + K P^2 = 0 for every turn radius the steering can reach (the
  // smaller root is K w^2).
  const double l = g_.wheelbase_m;
  const double k = l * l + t * t / 4;
  const double s = (left_mps * left_mps + right_mps * right_mps) / 2;
  const double p = (right_mps * right_mps - left_mps * left_mps) / (2 * t);
  const double disc = std::max(0.0, s * s - 4 * k * p * p);  // < 0 only from measurement noise
  const double v_abs = std::sqrt((s + std::sqrt(disc)) / 2);
  if (v_abs == 0) return {};
  const double v = (left_mps + right_mps) < 0 ? -v_abs : v_abs;
  return {v, p / v};
}

std::chrono::nanoseconds unambiguous_tick_gap(const ChassisGeometry& g, unsigned width_bytes,
                                              double max_wheel_speed_mps) {
  if ((width_bytes != 1 && width_bytes != 2 && width_bytes != 4) || !(max_wheel_speed_mps > 0))
    throw std::invalid_argument("tick gap: width must be 1, 2 or 4 bytes and the speed > 0");
  const double half_range = std::ldexp(1.0, 8 * static_cast<int>(width_bytes) - 1);
  const double max_ticks_per_s = max_wheel_speed_mps / (2 * std::numbers::pi * g.wheel_radius_m) * g.ticks_per_rev;
  return std::chrono::nanoseconds(static_cast<std::int64_t>(half_range / max_ticks_per_s * 1e9));
}

}  // namespace advee::driver_rs485
