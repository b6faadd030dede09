// SPDX-License-Identifier: GPL-2.0
// The CAN controller's state changes (from the kernel's error frames) as
// module error reports (number kErrBus): bus-off is an error, error-passive
// and error-warning are warnings, error-active again is a notice. Only
// changes are reported; the port holds transmission while bus-off.
// The master reports the same changes on the bus as its own EMCY errors
// (CiA 301): 0x8120 while error-passive, 0x8140 from bus-off until the
// controller is back (the EMCY goes out once transmission resumes).
#pragma once

#include <cstdint>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "advee/canopen/socketcan.hpp"
#include "advee/module/error.hpp"

namespace advee::driver_canbus {

struct BusReport {
  module::Severity severity;
  std::string text;
  // The master's EMCY errors this change makes active (true) or clears, in
  // the order to apply them (Master::set_error): raised before cleared, so
  // that a reset's error register shows the error that replaced it.
  std::vector<std::pair<std::uint16_t, bool>> emcy;
};

class BusStateReporter {
 public:
  explicit BusStateReporter(std::string ifname) : ifname_(std::move(ifname)) {}
  // The report for this error frame, nullopt when the state did not change.
  std::optional<BusReport> on_error(const canopen::CanErrorInfo& e);

 private:
  std::string ifname_;
  canopen::CanControllerState state_ = canopen::CanControllerState::kErrorActive;
};

}  // namespace advee::driver_canbus
