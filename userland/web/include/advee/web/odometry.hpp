// SPDX-License-Identifier: GPL-2.0
// The robot's position from its odometry alone (LL_DATA_ODO integrated), kept
// by the bridge rather than by each page, so that a page opened late shows
// the same estimate as one open from the start.
#pragma once

#include <string>

#include <nlohmann/json.hpp>

#include "advee/pose_integrator.hpp"

namespace advee::web {

// The channel of the bridge's own pose messages.
inline constexpr const char* kOdoPoseChannel = "WEB_ODO_POSE";

struct Pose2 {
  double x = 0, y = 0, heading = 0;  // world frame: m, m, rad counter-clockwise
};

// The diagnostic centre's dead reckoning (advee/pose_integrator.hpp), as
// the bridge's own channel.
class OdometryIntegrator {
 public:
  explicit OdometryIntegrator(Pose2 start = {}) { odo_.reset({start.x, start.y, start.heading}); }
  // One LL_DATA_ODO sample: constant speed and yaw rate over interval_s,
  // integrated exactly along the arc (as driver_rs485 does).
  void add(double speed_mps, double yaw_rate_radps, double interval_s) {
    odo_.advance(speed_mps, yaw_rate_radps, interval_s);
  }
  Pose2 pose() const { return {odo_.pose().x_m, odo_.pose().y_m, odo_.pose().heading_rad}; }
  // {"channel":"WEB_ODO_POSE","utime":..,"x_m","y_m","heading_rad"}, heading in (-pi, pi].
  nlohmann::json to_json(long long utime) const;

 private:
  PoseIntegrator odo_;
};

}  // namespace advee::web
