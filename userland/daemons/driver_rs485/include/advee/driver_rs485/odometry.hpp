// SPDX-License-Identifier: GPL-2.0
// Wheel speeds to body speeds for the robot's Ackermann chassis (thesis 4.4:
// the BR-SO1 counts the encoders of the non-driven front wheels, which do not
// slip). The reference point is the middle of the rear axle, x forward,
// y left, yaw counter-clockwise positive; the instantaneous centre of
// rotation lies on the rear axle line.
//
// For a rear-axle speed v and a yaw rate w, a wheel at position p (relative
// to the reference point) moves at |(v, 0) + w x p|. The front wheels sit at
// (wheelbase, +-track/2), so
//   v_fl^2 = v^2 - v w T + w^2 (L^2 + T^2/4)
//   v_fr^2 = v^2 + v w T + w^2 (L^2 + T^2/4)
// which inverts in closed form (from_wheel_speeds): v^2 and K w^2 (K = L^2 +
// T^2/4) are the two roots of x^2 - S x + K P^2 with S the mean of the
// squares and P = (v_fr^2 - v_fl^2) / 2T. v^2 is the larger one while the
// turn radius |v/w| is at least sqrt(K) (0.67 m for the example robot: the
// inner wheel steered less than 56 degrees, beyond the steering's reach), so
// the inversion is unique for every turn the robot can drive. Encoders on
// the rear axle instead give the differential-drive formulas.
#pragma once

#include <Eigen/Core>
#include <chrono>

namespace advee::driver_rs485 {

struct ChassisGeometry {
  double wheel_radius_m = 0.1;
  double ticks_per_rev = 1024;  // encoder ticks per wheel revolution
  double track_m = 0.5;         // distance between the left and right wheels
  double wheelbase_m = 0.6;     // front axle to rear axle
  bool encoders_on_front = true;  // steered front wheels (Ackermann); false: rear axle
};

struct BodySpeed {
  double speed_mps = 0;       // of the middle of the rear axle, forward positive
  double yaw_rate_radps = 0;  // counter-clockwise positive
};

class AckermannOdometry {
 public:
  explicit AckermannOdometry(const ChassisGeometry& g);

  const ChassisGeometry& geometry() const { return g_; }
  // Distance a wheel rolls for `ticks` encoder ticks.
  double metres_per_tick() const { return metres_per_tick_; }

  // Body speed from tick counts over `interval_s` (> 0).
  BodySpeed from_ticks(double ticks_left, double ticks_right, double interval_s) const;
  // Body speed from the signed ground speeds of the encoder wheels.
  BodySpeed from_wheel_speeds(double left_mps, double right_mps) const;
  // The forward model: signed ground speeds (left, right) of the encoder
  // wheels for a body speed (the sign is that of the wheel's rolling
  // direction, i.e. of v for the steered front wheels).
  Eigen::Vector2d wheel_speeds(const BodySpeed& s) const;

 private:
  ChassisGeometry g_;
  double metres_per_tick_;
  Eigen::Vector2d left_pos_, right_pos_;  // encoder wheels relative to the reference point
};

// The longest time between two GET_TICKS readings over which their
// difference is unambiguous: a wheel rolling at `max_wheel_speed_mps` stays
// below half the range of a `width_bytes` counter (TickAccumulator takes the
// shortest way round). A longer gap could hide a wrap; a shorter one only
// misses ticks if the board reset.
std::chrono::nanoseconds unambiguous_tick_gap(const ChassisGeometry& g, unsigned width_bytes,
                                              double max_wheel_speed_mps);

}  // namespace advee::driver_rs485
