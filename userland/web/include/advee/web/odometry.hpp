// SPDX-License-Identifier: GPL-2.0
// The robot's position from its odometry alone (LL_DATA_ODO integrated), kept
// by the bridge rather than by each page, so that a page opened late shows
// the same estimate as one open from the start.
#pragma once

#include <string>

#include <nlohmann/json.hpp>

namespace advee::web {

// The channel of the bridge's own pose messages.
inline constexpr const char* kOdoPoseChannel = "WEB_ODO_POSE";

struct Pose2 {
  double x = 0, y = 0, heading = 0;  // world frame: m, m, rad counter-clockwise
};

class OdometryIntegrator {
 public:
  explicit OdometryIntegrator(Pose2 start = {}) : pose_(start) {}
  // One LL_DATA_ODO sample: constant speed and yaw rate over interval_s,
  // integrated exactly along the arc (as driver_rs485 does).
  void add(double speed_mps, double yaw_rate_radps, double interval_s);
  const Pose2& pose() const { return pose_; }
  // {"channel":"WEB_ODO_POSE","utime":..,"x_m","y_m","heading_rad"}, heading in (-pi, pi].
  nlohmann::json to_json(long long utime) const;

 private:
  Pose2 pose_;
};

}  // namespace advee::web
