// SPDX-License-Identifier: GPL-2.0
// Ackermann kinematics about the middle of the rear axle (the frame the
// driver_rs485 odometry uses): yaw rate w = v tan(steering) / wheelbase; the
// front wheels at (wheelbase, +-track/2) roll |(v, 0) + w x p|.
#pragma once

#include <array>

#include "advee/robotsim/geometry.hpp"

namespace advee::robotsim {

// The pose after driving dt seconds at rear-axle speed v (m/s, forward
// positive) and yaw rate w (rad/s), integrated exactly along the arc.
Pose integrate_arc(const Pose& p, double v, double w, double dt);

// Yaw rate of the chassis for a speed and a (virtual, bicycle) steering angle.
double yaw_rate(double v, double steering_rad, double wheelbase_m);

// Signed distances rolled by the left and right front wheels in dt (sign of v).
std::array<double, 2> front_wheel_distances(double v, double w, double wheelbase_m, double track_m,
                                            double dt);

// Rear-axle distance and heading change from the distances rolled by the
// front wheels (inverse of front_wheel_distances; unique while the turn
// radius exceeds sqrt(wheelbase^2 + track^2/4)).
struct Motion {
  double distance = 0, heading_change = 0;
};
Motion motion_from_front_wheels(double left_m, double right_m, double wheelbase_m, double track_m);

}  // namespace advee::robotsim
