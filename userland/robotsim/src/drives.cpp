// SPDX-License-Identifier: GPL-2.0
#include "advee/robotsim/drives.hpp"

#include <cmath>

namespace advee::robotsim {

using canopen::sim::DriveProfile;
using canopen::sim::DriveSimConfig;

DriveSimConfig epos_config(const DriveUnits& u) {
  DriveSimConfig c;
  c.node = u.propulsion_node;
  c.profile = DriveProfile::kEpos;
  // Keeps DriveSim's EPOS position units (HEDL 5540, 500 lines at 4x per motor turn).
  return c;
}

DriveSimConfig icla_config(const DriveUnits& u) {
  DriveSimConfig c;
  c.node = u.steering_node;
  c.profile = DriveProfile::kIcla;
  c.position_per_velocity = 1.0;  // profile velocity in user units per second
  const double per_deg = deg_to_rad(1.0) * u.steering_units_per_rad;
  // The switch is part of the steering linkage: it sits at a steering angle,
  // the shaft starts at another; homing sets 0x6064 to the offset there, so
  // that 0 is straight ahead whatever angle the switch is at.
  c.home_switch_travel = (u.home_switch_deg - u.start_steering_deg) * per_deg;
  c.home_offset = static_cast<std::int32_t>(std::lround(u.home_switch_deg * per_deg));
  return c;
}

DrivePair::DrivePair(const DriveUnits& units, canopen::FrameSender send, canopen::NowFn now)
    : units_(units), epos_(epos_config(units), send, now), icla_(icla_config(units), send, now) {}

void DrivePair::power_on() {
  epos_.power_on();
  icla_.power_on();
}

void DrivePair::handle(const canopen::CanFrame& f) {
  // A broadcast (NMT, SYNC) goes to both; every other frame is ignored by
  // the drive it is not addressed to.
  epos_.handle(f);
  icla_.handle(f);
}

void DrivePair::poll() {
  epos_.poll();
  icla_.poll();
}

std::optional<canopen::TimePoint> DrivePair::deadline() const {
  const auto a = epos_.deadline(), b = icla_.deadline();
  if (!a) return b;
  if (!b) return a;
  return std::min(*a, *b);
}

DriveMotion DrivePair::motion() const {
  DriveMotion m;
  m.speed_mps = epos_.velocity() / units_.rpm_per_mps();
  m.steering_rad = deg_to_rad(units_.start_steering_deg) + icla_.travel() / units_.steering_units_per_rad;
  return m;
}

}  // namespace advee::robotsim
