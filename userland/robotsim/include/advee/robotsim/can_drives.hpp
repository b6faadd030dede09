// SPDX-License-Identifier: GPL-2.0
// The robot's drives on a SocketCAN interface (vcan0 in tests, where
// driver_canbus or advee-canopenctl is the master): a DrivePair on its own event
// loop thread, as advee-canopen-sim-drive runs one drive. advee-robot-sim's loop reads
// the motion through command(); a mutex keeps the two threads apart.
#pragma once

#include <exception>
#include <memory>
#include <mutex>
#include <string>
#include <thread>

#include "advee/canopen/can_port.hpp"
#include "advee/canopen/event_loop.hpp"
#include "advee/canopen/sim/drive_sim.hpp"
#include "advee/robotsim/drives.hpp"
#include "advee/robotsim/sinks.hpp"

namespace advee::robotsim {

// A snapshot of the drives for printing and the ground-truth message.
struct DriveStatus {
  canopen::cia402::State epos_state, icla_state;
  double epos_rpm = 0;           // actual velocity, motor rpm
  double icla_position = 0;      // 0x6064, user units
};

class CanDrives : public DriveSource {
 public:
  // Opens the interface and boots both drives; throws std::system_error.
  CanDrives(const std::string& ifname, const DriveUnits& units);
  ~CanDrives() override;
  CanDrives(const CanDrives&) = delete;
  CanDrives& operator=(const CanDrives&) = delete;

  // The chassis' speed and steering from the drives; rethrows what stopped
  // the drives' thread (a CAN socket error) as std::runtime_error.
  DriveCommand command(double time_s) override;
  DriveStatus status();

  // Fault injection, as advee-canopen-sim-drive's signals: EMCY + fault on a node,
  // heartbeat (and node guarding) silence of both drives on/off.
  void inject_fault(std::uint8_t node, std::uint16_t emcy_code);
  bool toggle_heartbeat_silence();

 private:
  void check_thread() const;

  canopen::EventLoop loop_;
  std::mutex mutex_;  // guards drives_ (and the CanPort it sends through)
  std::unique_ptr<canopen::CanPort> port_;
  std::unique_ptr<DrivePair> drives_;
  std::exception_ptr failure_;  // set by the loop thread before it ends
  std::thread thread_;          // last: starts once everything above exists
};

}  // namespace advee::robotsim
