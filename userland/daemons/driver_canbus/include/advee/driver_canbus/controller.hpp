// SPDX-License-Identifier: GPL-2.0
// The motion layer of driver_canbus (thesis 6.5) on a passive CANopen master:
// boots the EPOS (profile velocity) and the IclA (profile position), turns
// motion commands into a motor speed and a steering position, quick-stops the
// propulsion when commands stop for the configured timeout, holds all motion
// while LL_EVENT_STOP is engaged or the module is paused, homes the steering
// and refuses steering until it is homed, and boots a rebooted drive again.
//
// Like the master it has no thread and no clock of its own: everything runs
// on the thread that feeds the master (the daemon's CAN loop, or a unit test
// with a virtual bus and a manual clock). Reports leave through a callback.
#pragma once

#include <array>
#include <cstdint>
#include <functional>
#include <optional>
#include <string>

#include "advee/canopen/drivers/epos.hpp"
#include "advee/canopen/drivers/icla.hpp"
#include "advee/canopen/motion_watchdog.hpp"
#include "advee/driver_canbus/config.hpp"
#include "advee/module/error.hpp"

namespace advee::driver_canbus {

// Numbers of the reports on CM_DATA_ERROR (docs/daemons.md).
enum ErrorNumber : int {
  kErrBoot = 1,             // error: a drive could not be booted
  kErrCommandTimeout = 2,   // warning: no LL_CMD_MOTION for the timeout, propulsion quick stop
  kErrClamped = 3,          // warning: steering or speed beyond its limit, clamped
  kErrNotHomed = 4,         // warning: steering refused until homed
  kErrEmcy = 5,             // error: EMCY from a drive (notice for "error reset")
  kErrFault = 6,            // error: a drive entered fault
  kErrHeartbeatLost = 7,    // error: a drive's heartbeat stopped
  kErrHeartbeatResumed = 8, // notice
  kErrRebooted = 9,         // warning: a drive rebooted and is booted again
  kErrBooted = 10,          // notice: a drive is booted (again)
  kErrHoming = 11,          // error: homing failed; notice: homing done
  kErrStop = 12,            // notice: LL_EVENT_STOP engaged/released
  kErrDrive = 13,           // error: a drive did not follow a command (enable, move, quick stop)
  kErrRefused = 14,         // warning: a command refused (stopped, not ready, unknown axis)
  kErrBus = 15,             // CAN controller: error bus-off, warning error-passive/-warning, notice active again
};

enum class Axis : std::int8_t { kPropulsion = 0, kSteering = 1 };

struct DriveStatus {
  Axis axis = Axis::kPropulsion;
  std::uint8_t node = 0;
  std::string state = "offline";  // CiA 402 state, "offline" while not booted or heartbeat lost
  bool fault = false;
  std::int32_t error_code = 0;    // last EMCY code, 0 = none
  bool homed = false;
};

struct DrivesStatus {
  std::array<DriveStatus, 2> drives;  // propulsion, steering
  double speed_mps = 0;               // from 0x606C
  double steering_rad = 0;            // from 0x6064
  double cmd_speed_mps = 0;           // last sent to the drives
  double cmd_steering_rad = 0;
  bool stopped = true;
  std::string stop_reason;
};

class DriveController final : public canopen::TimedService {
 public:
  using Report = std::function<void(module::Severity, module::ErrorType, int number, std::string text)>;
  using Started = std::function<void(bool ok, std::string why)>;

  DriveController(canopen::Master& master, ControllerConfig cfg, Report report);
  DriveController(const DriveController&) = delete;
  DriveController& operator=(const DriveController&) = delete;

  // Boots both drives and enables them (speed 0), then homes the steering if
  // configured. `done` runs once both drives are enabled or one failed.
  void start(Started done);
  bool ready() const;

  void motion(double speed_mps, double steering_rad);  // LL_CMD_MOTION
  void stop_event(bool engaged);                       // LL_EVENT_STOP
  void home_steering();                                // LL_CMD_HOMING axis=steering
  void pause();                                        // module PAUSE: stop, send no targets
  void resume();                                       // module RUN: the next command moves

  DrivesStatus status() const;
  bool steering_homed() const { return homed_; }
  canopen::drivers::EposDriver& epos() { return epos_; }
  canopen::drivers::IclaDriver& icla() { return icla_; }
  const ControllerConfig& config() const { return cfg_; }

  void poll() override;
  std::optional<canopen::TimePoint> deadline() const override;

 private:
  struct Unit {
    Unit(Axis a, canopen::Drive402* d, std::string n) : axis(a), drive(d), name(std::move(n)) {}
    Axis axis;
    canopen::Drive402* drive;
    std::string name;
    bool booting = false;
    bool online = false;  // booted and heartbeat present
    bool heartbeat_lost = false;  // since the loss, until it resumes or the drive reboots
    bool enabling = false;
    std::int32_t emcy = 0;
    std::optional<canopen::TimePoint> reboot_at;      // boot again then
    std::optional<canopen::TimePoint> enable_after;   // no enable attempt before then (after a failure)
  };

  void boot(Unit& u, std::function<void(bool)> then);
  void on_drive_event(Unit& u, const canopen::DriveEvent& e);
  // The master's own EMCY 0x8130 (heartbeat error) is active while a drive's
  // heartbeat is lost.
  void update_heartbeat_error();
  // Enables the drive (fault reset included) unless held, then on_enabled().
  void ensure_enabled(Unit& u);
  // Sends what waited for the drive: the speed, the homing, the steering.
  void on_enabled(Unit& u);
  // retry: this is the second handshake after a set-point timeout.
  void send_pending_steering(bool retry = false);
  void start_homing();
  void quick_stop_propulsion(const std::string& why);
  void quick_stop_all(const std::string& why);
  bool held() const { return paused_ || stop_engaged_; }
  void report(module::Severity s, module::ErrorType t, int n, std::string text) {
    if (report_) report_(s, t, n, std::move(text));
  }

  canopen::Master& master_;
  ControllerConfig cfg_;
  Report report_;
  canopen::drivers::EposDriver epos_;
  canopen::drivers::IclaDriver icla_;
  Unit prop_;
  Unit steer_;
  canopen::MotionWatchdog watchdog_;

  bool started_ = false;
  bool paused_ = false;
  bool stop_engaged_ = false;
  bool timed_out_ = false;
  bool homed_ = false;
  bool homing_ = false;
  bool homing_requested_ = false;  // waits for the IclA to be enabled
  bool homing_joined_ = false;     // a second request joined this homing (reported once)
  double cmd_speed_ = 0;
  double cmd_steering_ = 0;
  std::optional<double> pending_speed_;     // waiting for the EPOS to be enabled
  std::optional<double> pending_steering_;  // waiting for enable or the running move
  bool moving_ = false;                     // an IclA set-point is running
  std::optional<double> sent_steering_;     // last target the IclA reached or runs to
  // Warnings that would repeat with every command at 10 Hz are reported once
  // per episode.
  bool warned_clamp_ = false;
  bool warned_speed_clamp_ = false;
  bool warned_not_homed_ = false;
  bool warned_refused_ = false;
  Registration service_;  // last: polled only while everything above exists
};

}  // namespace advee::driver_canbus
