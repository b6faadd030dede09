// SPDX-License-Identifier: GPL-2.0
#include "advee/rs485_daemon/node_health.hpp"

#include <cstdio>

#include "advee/rs485/error.hpp"

namespace advee::rs485_daemon {

using module::ErrorType;
using module::Severity;

std::string NodeHealth::label() const {
  char buf[16];
  std::snprintf(buf, sizeof buf, " (0x%02x)", addr_);
  return name_ + buf;
}

void NodeHealth::update_state(const NodeStatusFn& status) {
  if (!status) return;
  const auto s = status(addr_);
  if (!s || s->state == state_) return;
  const auto was = state_;
  state_ = s->state;
  char hex[8];
  std::snprintf(hex, sizeof hex, "0x%02x", addr_);
  switch (state_) {
    case rs485::NodeState::passive:
      if (was == rs485::NodeState::active)
        errors_.report(Severity::Warning, ErrorType::Device, kErrPassive,
                       label() + " is error-passive (error counter " + std::to_string(s->errors) + ")");
      else
        errors_.report(Severity::Notice, ErrorType::Device, kErrRecovered,
                       label() + " was reset: polling it again (error-passive)");
      break;
    case rs485::NodeState::off:
      errors_.report(Severity::Error, ErrorType::Device, kErrOff,
                     label() + " is off (error counter " + std::to_string(s->errors) +
                         "): not polled until reset (advee-rs485ctl reset-node " + hex + ")");
      break;
    case rs485::NodeState::active:
      errors_.report(Severity::Notice, ErrorType::Device, kErrRecovered,
                     label() + (was == rs485::NodeState::off ? " was reset: polling it again"
                                                             : " is error-active again"));
      break;
  }
}

bool NodeHealth::may_poll(const NodeStatusFn& status) {
  update_state(status);
  return state_ != rs485::NodeState::off;
}

void NodeHealth::record(std::string_view what, std::error_code outcome, const NodeStatusFn& status) {
  if (outcome && !failing_) {
    const bool timeout = outcome == rs485::Outcome::timeout;
    errors_.report(Severity::Warning, timeout ? ErrorType::Timeout : ErrorType::Device, kErrTransaction,
                   label() + ": " + std::string(what) + " failed: " + outcome.message());
  } else if (!outcome && failing_) {
    errors_.report(Severity::Notice, ErrorType::Device, kErrRecovered, label() + " answers again");
  }
  failing_ = static_cast<bool>(outcome);
  update_state(status);
}

}  // namespace advee::rs485_daemon
