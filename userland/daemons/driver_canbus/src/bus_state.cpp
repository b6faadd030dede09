// SPDX-License-Identifier: GPL-2.0
#include "advee/driver_canbus/bus_state.hpp"

namespace advee::driver_canbus {

using canopen::CanControllerState;
using module::Severity;

std::optional<BusReport> BusStateReporter::on_error(const canopen::CanErrorInfo& e) {
  if (!e.state || *e.state == state_) return std::nullopt;
  const CanControllerState was = state_;
  state_ = *e.state;
  const std::string head = "CAN controller " + ifname_ + ": ";
  switch (state_) {
    case CanControllerState::kBusOff:
      return BusReport{Severity::Error, head + "bus-off, transmission held until the controller restarts"};
    case CanControllerState::kErrorPassive:
      return BusReport{Severity::Warning, head + "error-passive"};
    case CanControllerState::kErrorWarning:
      return BusReport{Severity::Warning, head + "error-warning"};
    case CanControllerState::kErrorActive:
      return BusReport{Severity::Notice, head + "error-active again (was " + std::string(to_string(was)) + ")"};
  }
  return std::nullopt;
}

}  // namespace advee::driver_canbus
