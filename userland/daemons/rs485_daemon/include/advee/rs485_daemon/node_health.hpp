// SPDX-License-Identifier: GPL-2.0
// Health of one polled node, reported through the module's error reporter:
// the first failed transaction of a run of failures (warning), the first
// good one after it (notice), and the kernel's CAN-like error state of the
// node (rs485-protocol.md): error-passive (warning) and off (error). An off
// node is not polled until its counter is reset (`advee-rs485ctl reset-node`), as
// the protocol requires; polling resumes by itself once it is.
#pragma once

#include <cstdint>
#include <functional>
#include <optional>
#include <string>
#include <system_error>

#include "advee/module/error.hpp"
#include "advee/rs485/bus.hpp"

namespace advee::rs485_daemon {

// The kernel's view of a node (Bus::node); nullopt when it cannot be read
// (a transport without node state, such as FakeTransport).
using NodeStatusFn = std::function<std::optional<rs485::NodeStatus>(std::uint8_t addr)>;

// Error numbers on CM_DATA_ERROR, the same for every RS-485 daemon; each
// daemon numbers its own from 5 on.
inline constexpr int kErrTransaction = 1;  // a transaction failed (text names the outcome)
inline constexpr int kErrPassive = 2;      // node error-passive
inline constexpr int kErrOff = 3;          // node off: no longer polled
inline constexpr int kErrRecovered = 4;    // answers again / polled again (notice)

class NodeHealth {
 public:
  NodeHealth(module::ErrorReporter& errors, std::string name, std::uint8_t addr)
      : errors_(errors), name_(std::move(name)), addr_(addr) {}

  // Before a poll: false while the node is off.
  bool may_poll(const NodeStatusFn& status);
  // After a transaction `what` (e.g. "GET_BOTH") with its outcome.
  void record(std::string_view what, std::error_code outcome, const NodeStatusFn& status);

  bool failing() const { return failing_; }
  rs485::NodeState state() const { return state_; }
  std::string label() const;  // "front (0x10)"

 private:
  void update_state(const NodeStatusFn& status);

  module::ErrorReporter& errors_;
  std::string name_;
  std::uint8_t addr_;
  bool failing_ = false;
  rs485::NodeState state_ = rs485::NodeState::active;
};

}  // namespace advee::rs485_daemon
