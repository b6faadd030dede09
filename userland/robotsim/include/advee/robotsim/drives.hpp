// SPDX-License-Identifier: GPL-2.0
// The robot's two drives as the canopen simulation library models them: a
// simulated EPOS (propulsion) and IclA (steering) on one CAN bus, and the
// coupling to the chassis: the robot's speed follows the EPOS's actual
// velocity, its steering angle the IclA's shaft. Passive like
// SimulatedDrive (handle, poll, deadline); CanDrives runs it on SocketCAN.
#pragma once

#include <optional>

#include "advee/canopen/clock.hpp"
#include "advee/canopen/frame.hpp"
#include "advee/canopen/sim/drive_sim.hpp"
#include "advee/robotsim/drive_units.hpp"

namespace advee::robotsim {

// What the drives make the chassis do.
struct DriveMotion {
  double speed_mps = 0;     // from the EPOS's actual velocity
  double steering_rad = 0;  // from the IclA's shaft, left positive
};

class DrivePair {
 public:
  DrivePair(const DriveUnits& units, canopen::FrameSender send, canopen::NowFn now);

  // Both drives boot (boot-up messages, pre-operational).
  void power_on();
  void handle(const canopen::CanFrame& f);
  void poll();
  std::optional<canopen::TimePoint> deadline() const;

  DriveMotion motion() const;
  canopen::sim::SimulatedDrive& epos() { return epos_; }
  canopen::sim::SimulatedDrive& icla() { return icla_; }
  const DriveUnits& units() const { return units_; }

 private:
  DriveUnits units_;
  canopen::sim::SimulatedDrive epos_;
  canopen::sim::SimulatedDrive icla_;
};

// The simulated drives' settings for these units (exposed for the tests).
canopen::sim::DriveSimConfig epos_config(const DriveUnits& u);
canopen::sim::DriveSimConfig icla_config(const DriveUnits& u);

}  // namespace advee::robotsim
