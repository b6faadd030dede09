// SPDX-License-Identifier: GPL-2.0
// Dead reckoning from LL_DATA_ODO: each message gives the speed of the
// reference point and the yaw rate over its interval; integrating them along
// a circular arc (constant v and w over the interval) gives the position
// estimate that the thesis's diagnostic centre shows. Arcs, not Euler steps:
// at 4 Hz a turn of 0.4 rad/s would otherwise drift outwards.
#pragma once

namespace advee {

struct Pose {
  double x_m = 0;
  double y_m = 0;
  double heading_rad = 0;  // counter-clockwise from the x axis, wrapped to (-pi, pi]
};

class PoseIntegrator {
 public:
  // Advance by one interval of constant speed (m/s) and yaw rate (rad/s).
  // Intervals that are not finite or not positive are ignored (a broken
  // message must not teleport the estimate).
  void advance(double speed_mps, double yaw_rate_radps, double interval_s);
  void reset(const Pose& p = {}) {
    pose_ = p;
    distance_m_ = 0;
  }
  const Pose& pose() const { return pose_; }
  double distance_m() const { return distance_m_; }  // path length driven (|v| dt summed)

 private:
  Pose pose_;
  double distance_m_ = 0;
};

double wrap_angle(double rad);  // to (-pi, pi]

}  // namespace advee
