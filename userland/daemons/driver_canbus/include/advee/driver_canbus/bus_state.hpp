// SPDX-License-Identifier: GPL-2.0
// The CAN controller's state changes (from the kernel's error frames) as
// module error reports (number kErrBus): bus-off is an error, error-passive
// and error-warning are warnings, error-active again is a notice. Only
// changes are reported; the port holds transmission while bus-off.
#pragma once

#include <optional>
#include <string>

#include "advee/canopen/socketcan.hpp"
#include "advee/module/error.hpp"

namespace advee::driver_canbus {

struct BusReport {
  module::Severity severity;
  std::string text;
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
