// SPDX-License-Identifier: GPL-2.0
// driver_canbus's wiring: the module (LCM, state machine, reports) on the
// main thread, the CANopen master and the DriveController on a CAN loop
// thread of their own. LCM commands and module state changes are posted to
// the CAN loop; reports and LL_DATA_DRIVES snapshots are posted back to the
// module. Nothing else crosses the threads.
#pragma once

#include <memory>
#include <optional>

#include "advee/canopen/event_loop.hpp"
#include "advee/canopen/runtime.hpp"
#include "advee/driver_canbus/bus_state.hpp"
#include "advee/driver_canbus/config.hpp"
#include "advee/driver_canbus/controller.hpp"
#include "advee/module/module.hpp"
#include "advee/module/subscription.hpp"
#include "lowlevel/cmd_homing_t.hpp"
#include "lowlevel/cmd_motion_t.hpp"
#include "lowlevel/event_stop_t.hpp"

namespace advee::driver_canbus {

// Exit details (module::ExitKind::Device + n).
inline constexpr int kExitNoInterface = 1;  // the CAN interface cannot be opened
inline constexpr int kExitBootFailed = 2;   // a drive cannot be booted at start-up
inline constexpr int kExitCanFailed = 3;    // the CAN loop failed (e.g. ENETDOWN: the interface went down)

class CanbusDriver {
 public:
  // Opens the interface (ModuleExit device 1 when it cannot) and starts the
  // CAN loop; the drives boot at once, a failure ends m.run() with device 2.
  // A failure of the CAN loop (an I/O error such as ENETDOWN when the
  // interface goes down) ends m.run() with device 3.
  CanbusDriver(module::Module& m, const CanbusConfig& cfg);
  ~CanbusDriver();
  CanbusDriver(const CanbusDriver&) = delete;
  CanbusDriver& operator=(const CanbusDriver&) = delete;

 private:
  void publish(const DrivesStatus& s);

  module::Module& m_;
  CanbusConfig cfg_;
  canopen::EventLoop loop_;
  BusStateReporter bus_state_;  // CAN thread only
  std::unique_ptr<canopen::MasterRuntime> runtime_;
  std::unique_ptr<DriveController> controller_;
  std::optional<module::Subscription<lowlevel::cmd_motion_t>> motion_sub_;
  std::optional<module::Subscription<lowlevel::cmd_homing_t>> homing_sub_;
  std::optional<module::Subscription<lowlevel::event_stop_t>> stop_sub_;
  std::unique_ptr<canopen::LoopThread> thread_;  // last: stopped and joined first
};

}  // namespace advee::driver_canbus
