// SPDX-License-Identifier: GPL-2.0
#include "advee/robotsim/robot.hpp"

#include <algorithm>
#include <cmath>

#include "advee/robotsim/kinematics.hpp"

namespace advee::robotsim {

namespace {
// A zero standard deviation means an exact sensor (std::normal_distribution needs > 0).
double gaussian(std::mt19937& rng, double sigma) {
  return sigma > 0 ? std::normal_distribution<double>(0, sigma)(rng) : 0.0;
}
}  // namespace

std::uint16_t bearing_to_cdeg(double bearing_rad) {
  double deg = std::fmod(rad_to_deg(bearing_rad), 360.0);
  if (deg < 0) deg += 360.0;
  const long cd = std::lround(deg * 100);
  return static_cast<std::uint16_t>(cd >= 36000 ? cd - 36000 : cd);
}

Robot::Robot(RobotDescription desc, World world, std::uint32_t seed)
    : desc_(std::move(desc)), world_(std::move(world)), rng_(seed), pose_(desc_.start) {
  for (const auto& ch : desc_.thermal) temps_.push_back(ch.ambient_c);
  bumper_ = bumper_contact(pose_);
}

std::vector<Vec2> Robot::footprint(const Pose& p) const {
  const auto& c = desc_.chassis;
  return {p.to_world({c.front_m, c.half_width_m}), p.to_world({-c.rear_m, c.half_width_m}),
          p.to_world({-c.rear_m, -c.half_width_m}), p.to_world({c.front_m, -c.half_width_m})};
}

std::uint8_t Robot::bumper_contact(const Pose& p) const {
  const double middle = (desc_.chassis.front_m - desc_.chassis.rear_m) / 2;
  std::uint8_t bits = 0;
  for (const Vec2& hit : world_.contacts(footprint(p)))
    bits |= p.to_robot(hit).x() >= middle ? kPauseFrontBumper : kPauseRearBumper;
  return bits;
}

void Robot::step(double speed, double steering, double dt) {
  const auto& c = desc_.chassis;
  speed = std::clamp(speed, -c.max_speed_mps, c.max_speed_mps);
  const double lim = deg_to_rad(c.max_steering_deg);
  steering = std::clamp(steering, -lim, lim);
  const double w = yaw_rate(speed, steering, c.wheelbase_m);
  const Pose next = integrate_arc(pose_, speed, w, dt);
  const std::uint8_t contact = bumper_contact(next);
  const bool powered = motor_powered();  // the PAUSE line as the step begins
  if (contact) {
    // The bumper stops the robot where it touched: no motion, no ticks.
    bumper_ = contact;
    speed_ = 0;
  } else if (!powered) {
    // PAUSE cut the motor: it stands; the bumper is free again.
    bumper_ = 0;
    speed_ = 0;
  } else {
    const auto d = front_wheel_distances(speed, w, c.wheelbase_m, c.track_m, dt);
    const double ticks_per_m = c.ticks_per_rev / (2 * kPi * c.wheel_radius_m);
    ticks_[0] += d[0] * ticks_per_m;
    ticks_[1] += d[1] * ticks_per_m;
    pose_ = next;
    bumper_ = 0;
    speed_ = speed;
  }
  steering_ = steering;
  for (std::size_t i = 0; i < temps_.size(); ++i) {
    const auto& ch = desc_.thermal[i];
    const double load = ch.load == ThermalChannel::Load::kPropulsion ? std::abs(speed_) / c.max_speed_mps
                                                                     : std::abs(steering_) / lim;
    const double target = ch.ambient_c + ch.gain_c * load;
    temps_[i] += (target - temps_[i]) * (1 - std::exp(-dt / ch.tau_s));
  }
  time_ += dt;
}

std::optional<double> Robot::srf_range(const RangeSensor& s) {
  const auto& m = desc_.srf;
  const Vec2 origin = pose_.to_world(s.position);
  // Five rays across the cone stand for the beam: the nearest echo answers.
  std::optional<double> best;
  constexpr int kRays = 5;
  for (int k = 0; k < kRays; ++k) {
    const double off = m.beam_half_angle_deg * (2.0 * k / (kRays - 1) - 1);
    const auto hit = world_.ray_cast(origin, pose_.world_angle(deg_to_rad(s.heading_deg + off)), m.max_m);
    if (hit && (!best || *hit < *best)) best = hit;
  }
  if (!best || *best < m.min_m) return std::nullopt;
  const double noisy = *best + gaussian(rng_, m.noise_m);
  return std::clamp(noisy, m.min_m, m.max_m);
}

SensorFrame Robot::sense() {
  SensorFrame f;
  f.time_s = time_;
  f.pose = pose_;
  f.speed_mps = speed_;
  f.steering_rad = steering_;
  f.ticks = {static_cast<std::int64_t>(std::floor(ticks_[0])), static_cast<std::int64_t>(std::floor(ticks_[1]))};
  f.pause = bumper_;
  for (const auto& s : desc_.srf.sensors) {
    f.srf_m.push_back(srf_range(s));
    if (desc_.srf.proximity_pause_m > 0 && f.srf_m.back() && *f.srf_m.back() < desc_.srf.proximity_pause_m)
      f.pause |= kPauseProximity;
  }
  const auto& ir = desc_.ir;
  for (std::size_t i = 0; i < ir.sensors.size(); ++i) {
    // The room's floor is flat: every IR sensor sees it at its mounting distance.
    const double d = ir.ground_m + gaussian(rng_, ir.noise_m);
    if (d < ir.min_m || d > ir.max_m) {
      f.ir_m.push_back(std::nullopt);
    } else {
      f.ir_m.push_back(d);
    }
    if (!f.ir_m.back() || std::abs(*f.ir_m.back() - ir.ground_m) > ir.pause_deviation_m) f.pause |= kPauseGround;
  }
  const auto& sc = desc_.scanner;
  const Vec2 eye = pose_.to_world(sc.position);
  for (const auto& b : world_.beacons()) {
    const double dist = (b.position - eye).norm();
    if (dist > sc.max_range_m || !world_.line_of_sight(eye, b.position)) continue;
    const Vec2 rel = b.position - eye;
    const double bearing = std::atan2(rel.y(), rel.x()) - pose_.heading +
                           deg_to_rad(gaussian(rng_, sc.noise_deg));
    const double q = std::clamp(255.0 * (1 - dist / sc.max_range_m), 1.0, 255.0);
    f.beacons.push_back({b.id, bearing_to_cdeg(bearing), static_cast<std::uint8_t>(std::lround(q))});
  }
  f.temperature_c = temps_;
  sensed_pause_ = f.pause & static_cast<std::uint8_t>(~(kPauseFrontBumper | kPauseRearBumper));
  return f;
}

}  // namespace advee::robotsim
