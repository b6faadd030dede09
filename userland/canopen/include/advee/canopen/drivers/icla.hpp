// SPDX-License-Identifier: GPL-2.0
// Berger Lahr IclA steering drive (thesis 4.2, 6.4.2): profile position via
// RPDO2 (controlword + 0x607A), position feedback via TPDO2 (statusword +
// 0x6064), homing on the mechanical home switch. The IclA's real PDO defaults
// and units are not verified (canopen-notes.md §3.14): the mapping is read
// back and the boot fails (or remaps, if configured) when it differs.
#pragma once

#include <cstdint>

#include "advee/canopen/drive402.hpp"

namespace advee::canopen::drivers {

struct IclaConfig {
  std::uint8_t node = 2;
  double units_per_rad = 1000.0;    // position user units per steering radian
  std::int8_t homing_method = 19;   // home switch (CiA 402 19-22)
  std::int32_t home_offset = 0;
  std::uint32_t homing_speed = 500;  // switch search, user units
  std::uint32_t homing_acceleration = 1000;
  std::uint32_t profile_velocity = 1000;
  DriveConfig drive;
};

class IclaDriver {
 public:
  using Done = Drive402::Done;
  IclaDriver(Master& master, IclaConfig cfg);

  void boot(Done done);
  void enable(Done done) { drive_.enable(std::move(done)); }
  // Writes method/speeds/offset (SDO), homing mode, start, then back to pp.
  void home(Done done);
  void set_angle(double rad, Done done);
  std::optional<double> angle() const;
  Drive402& drive() { return drive_; }

 private:
  IclaConfig cfg_;
  Drive402 drive_;
};

}  // namespace advee::canopen::drivers
