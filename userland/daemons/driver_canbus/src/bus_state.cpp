// SPDX-License-Identifier: GPL-2.0
#include "advee/driver_canbus/bus_state.hpp"

namespace advee::driver_canbus {

using canopen::CanControllerState;
using module::Severity;

namespace {

std::vector<std::pair<std::uint16_t, bool>> emcy_changes(CanControllerState was, CanControllerState now) {
  using canopen::kEmcyBusOffRecovered;
  using canopen::kEmcyCanErrorPassive;
  std::vector<std::pair<std::uint16_t, bool>> raised, cleared;
  const auto change = [&](std::uint16_t code, bool before, bool after) {
    if (after && !before) raised.emplace_back(code, true);
    if (before && !after) cleared.emplace_back(code, false);
  };
  change(kEmcyCanErrorPassive, was == CanControllerState::kErrorPassive, now == CanControllerState::kErrorPassive);
  change(kEmcyBusOffRecovered, was == CanControllerState::kBusOff, now == CanControllerState::kBusOff);
  raised.insert(raised.end(), cleared.begin(), cleared.end());
  return raised;
}

}  // namespace

std::optional<BusReport> BusStateReporter::on_error(const canopen::CanErrorInfo& e) {
  if (!e.state || *e.state == state_) return std::nullopt;
  const CanControllerState was = state_;
  state_ = *e.state;
  const std::string head = "CAN controller " + ifname_ + ": ";
  auto emcy = emcy_changes(was, state_);
  switch (state_) {
    case CanControllerState::kBusOff:
      return BusReport{Severity::Error, head + "bus-off, transmission held until the controller restarts",
                       std::move(emcy)};
    case CanControllerState::kErrorPassive:
      return BusReport{Severity::Warning, head + "error-passive", std::move(emcy)};
    case CanControllerState::kErrorWarning:
      return BusReport{Severity::Warning, head + "error-warning", std::move(emcy)};
    case CanControllerState::kErrorActive:
      return BusReport{Severity::Notice, head + "error-active again (was " + std::string(to_string(was)) + ")",
                       std::move(emcy)};
  }
  return std::nullopt;
}

}  // namespace advee::driver_canbus
