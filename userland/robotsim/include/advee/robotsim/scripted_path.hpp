// SPDX-License-Identifier: GPL-2.0
// A scripted drive: (speed, steering, duration) segments played in order,
// the stand-in for the simulated EPOS and IclA until they offer a hook; and
// the odometry check of the demo (ticks -> pose against the true pose).
#pragma once

#include <string>
#include <vector>

#include "advee/robotsim/geometry.hpp"
#include "advee/robotsim/robot.hpp"

namespace advee::robotsim {

struct PathSegment {
  double speed_mps = 0;
  double steering_rad = 0;
  double duration_s = 0;
};

class ScriptedPath {
 public:
  ScriptedPath() = default;
  explicit ScriptedPath(std::vector<PathSegment> segments);

  double duration() const { return duration_; }
  // The command at time t (seconds from the start); after the end: stop.
  PathSegment at(double t) const;
  const std::vector<PathSegment>& segments() const { return segments_; }

 private:
  std::vector<PathSegment> segments_;
  double duration_ = 0;
};

// File format: `path: [{speed_mps, steering_deg, duration_s}, ...]`.
ScriptedPath parse_path(const std::string& yaml_text, const std::string& name);
ScriptedPath load_path(const std::string& path);

// Dead reckoning from the BR-SO1's front-wheel tick counts, as driver_rs485
// does it: each sample's tick increments are taken as one constant arc.
class TickOdometry {
 public:
  // `left0`, `right0`: the counts at `start`.
  TickOdometry(const Chassis& c, const Pose& start, std::int64_t left0 = 0, std::int64_t right0 = 0);
  void update(std::int64_t left_ticks, std::int64_t right_ticks);  // cumulative counts
  const Pose& pose() const { return pose_; }

 private:
  Chassis c_;
  Pose pose_;
  std::int64_t last_[2] = {0, 0};
};

struct OdometryError {
  double position_m = 0;  // |odometry - true| at the end
  double heading_rad = 0;
  double distance_m = 0;  // path length driven (true)
};

// Drives `robot` along `path` in steps of dt, sampling the ticks every
// sample_period (as driver_rs485's poll would) into a TickOdometry.
OdometryError run_path(Robot& robot, const ScriptedPath& path, double dt, double sample_period);

}  // namespace advee::robotsim
