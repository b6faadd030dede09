// SPDX-License-Identifier: GPL-2.0
// Maxon EPOS 70/10 driving the robot's propulsion (thesis 4.2, 6.4.2):
// profile velocity mode, target velocity in rpm via RPDO4 (controlword +
// 0x60FF), velocity feedback via TxPDO4 (statusword + 0x606C), which is
// disabled by default and switched on at boot. Wheel speed in m/s is
// converted with the gear ratio (26:1) and the wheel radius from the
// configuration.
#pragma once

#include <cstdint>

#include "advee/canopen/drive402.hpp"

namespace advee::canopen::drivers {

struct EposConfig {
  std::uint8_t node = 1;
  double gear_ratio = 26.0;     // motor turns per wheel turn (GP52C 26:1)
  double wheel_radius_m = 0.1;  // from the robot's configuration
  std::uint32_t acceleration_rpm_s = 10000;
  std::uint32_t deceleration_rpm_s = 10000;
  std::uint32_t quick_stop_deceleration_rpm_s = 20000;
  DriveConfig drive;            // node and PDO fields are filled in by the driver
};

class EposDriver {
 public:
  using Done = Drive402::Done;
  EposDriver(Master& master, EposConfig cfg);

  // Boot (PDO read-back: RPDO4 must map 6040+60FF, TPDO4 6041+606C), ramps, pv mode.
  void boot(Done done);
  void enable(Done done) { drive_.enable(std::move(done)); }
  void quick_stop(Done done) { drive_.quick_stop(std::move(done)); }
  // Wheel surface speed; sent at once on RPDO4.
  bool set_speed(double m_per_s);
  std::optional<double> speed() const;  // from TxPDO4

  std::int32_t rpm_for(double m_per_s) const;
  double m_per_s_for(std::int32_t rpm) const;
  Drive402& drive() { return drive_; }

 private:
  EposConfig cfg_;
  Drive402 drive_;
};

}  // namespace advee::canopen::drivers
