// SPDX-License-Identifier: GPL-2.0
// The units of the robot's two CANopen drives, shared with driver_canbus
// (both read them from the `drives:` section of their YAML): the Maxon EPOS
// 70/10 propulsion drive's velocity in motor rpm, the Berger Lahr IclA
// steering drive's position in user units per radian of steering angle.
#pragma once

#include <cstdint>

#include "advee/robotsim/geometry.hpp"

namespace advee::robotsim {

struct DriveUnits {
  // Propulsion: RE50 motor, GP52C 26:1 gearhead, rear wheels of 0.125 m.
  std::uint8_t propulsion_node = 1;
  double gear_ratio = 26;           // motor revolutions per wheel revolution
  double drive_wheel_radius_m = 0.125;
  // Steering: 0x607A/0x6064 in units of 1/10000 rad, 0 = straight ahead
  // after homing, left positive.
  std::uint8_t steering_node = 2;
  double steering_units_per_rad = 10000;
  double home_switch_deg = 0;    // steering angle at which the IclA's home switch sits
  double start_steering_deg = 0;  // steering angle at power-on (before homing)

  // 0x60FF/0x606C motor rpm per m/s of robot speed: 60 * gear / (2 pi r).
  double rpm_per_mps() const { return 60.0 * gear_ratio / (2 * kPi * drive_wheel_radius_m); }
};

}  // namespace advee::robotsim
