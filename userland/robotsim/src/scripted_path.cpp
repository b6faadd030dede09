// SPDX-License-Identifier: GPL-2.0
#include "advee/robotsim/scripted_path.hpp"

#include <cmath>

#include "advee/robotsim/kinematics.hpp"
#include "yaml_util.hpp"

namespace advee::robotsim {

ScriptedPath::ScriptedPath(std::vector<PathSegment> segments) : segments_(std::move(segments)) {
  for (const auto& s : segments_) duration_ += s.duration_s;
}

PathSegment ScriptedPath::at(double t) const {
  for (const auto& s : segments_) {
    if (t < s.duration_s) return s;
    t -= s.duration_s;
  }
  return {};
}

ScriptedPath parse_path(const std::string& text, const std::string& name) {
  const yaml::Ctx c{name};
  const YAML::Node doc = yaml::parse(text, name);
  const YAML::Node list = yaml::need(c, doc, "path", "path");
  if (!list.IsSequence()) c.fail(list, "path", "expected a list of {speed_mps, steering_deg, duration_s}");
  std::vector<PathSegment> segs;
  for (std::size_t i = 0; i < list.size(); ++i) {
    const std::string f = "path[" + std::to_string(i) + "]";
    PathSegment s;
    s.speed_mps = yaml::number(c, yaml::need(c, list[i], "speed_mps", f + ".speed_mps"), f + ".speed_mps");
    s.steering_rad = deg_to_rad(yaml::number_or(c, list[i], "steering_deg", f + ".steering_deg", 0));
    s.duration_s = yaml::number(c, yaml::need(c, list[i], "duration_s", f + ".duration_s"), f + ".duration_s");
    if (!(s.duration_s > 0)) c.fail(list[i]["duration_s"], f + ".duration_s", "must be > 0");
    segs.push_back(s);
  }
  return ScriptedPath(std::move(segs));
}

ScriptedPath load_path(const std::string& path) { return parse_path(yaml::read_file(path), path); }

TickOdometry::TickOdometry(const Chassis& c, const Pose& start, std::int64_t left0, std::int64_t right0)
    : c_(c), pose_(start), last_{left0, right0} {}

void TickOdometry::update(std::int64_t left, std::int64_t right) {
  const double m_per_tick = 2 * kPi * c_.wheel_radius_m / c_.ticks_per_rev;
  const double dl = static_cast<double>(left - last_[0]) * m_per_tick;
  const double dr = static_cast<double>(right - last_[1]) * m_per_tick;
  last_[0] = left;
  last_[1] = right;
  const Motion m = motion_from_front_wheels(dl, dr, c_.wheelbase_m, c_.track_m);
  pose_ = integrate_arc(pose_, m.distance, m.heading_change, 1.0);
}

OdometryError run_path(Robot& robot, const ScriptedPath& path, double dt, double sample_period) {
  const auto whole = [&](int i) { return static_cast<std::int64_t>(std::floor(robot.exact_ticks()[i])); };
  TickOdometry odo(robot.description().chassis, robot.pose(), whole(0), whole(1));
  OdometryError err;
  const long steps = std::lround(path.duration() / dt);
  const long per_sample = std::max(1L, std::lround(sample_period / dt));
  for (long i = 0; i < steps; ++i) {
    const PathSegment cmd = path.at((static_cast<double>(i) + 0.5) * dt);
    const Vec2 before = robot.pose().position;
    robot.step(cmd.speed_mps, cmd.steering_rad, dt);
    err.distance_m += (robot.pose().position - before).norm();
    if ((i + 1) % per_sample == 0 || i + 1 == steps) {
      odo.update(whole(0), whole(1));
    }
  }
  err.position_m = (odo.pose().position - robot.pose().position).norm();
  err.heading_rad = std::abs(wrap_angle(odo.pose().heading - robot.pose().heading));
  return err;
}

}  // namespace advee::robotsim
