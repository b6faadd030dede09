// SPDX-License-Identifier: GPL-2.0
// Node guarding, the legacy error control of CiA 301 (canopen-notes.md §3.3):
// the master sends an RTR on 0x700 + node every guard time; the node answers
// with its NMT state in bits 6..0 and a toggle bit 7 that alternates from 0.
// No valid answer within guard time x life-time factor means the node is
// lost; an answer with the toggle bit not alternated does not count. Events
// use the heartbeat consumer's types so drivers treat both alike.
#pragma once

#include <cstdint>
#include <functional>
#include <map>
#include <optional>

#include "advee/canopen/clock.hpp"
#include "advee/canopen/frame.hpp"
#include "advee/canopen/heartbeat.hpp"

namespace advee::canopen {

class NodeGuarding {
 public:
  using Listener = std::function<void(const HeartbeatUpdate&)>;

  NodeGuarding(FrameSender send, NowFn now, Listener listener);

  // Starts guarding (first RTR at once); guard_time zero stops it.
  void guard(std::uint8_t node, Duration guard_time, std::uint8_t life_time_factor);
  // True for a reply of a guarded node (0x700 + node, DLC 1, not RTR).
  bool handle(const CanFrame& f);
  void poll();
  std::optional<TimePoint> deadline() const;

  bool lost(std::uint8_t node) const;
  std::uint64_t toggle_errors() const { return toggle_errors_; }

 private:
  struct Entry {
    Duration guard{};
    std::uint8_t factor = 1;
    TimePoint next_rtr{};
    TimePoint last_valid{};
    std::optional<bool> last_toggle;
    NmtState state = NmtState::kUnknown;
    bool lost = false;
  };
  FrameSender send_;
  NowFn now_;
  Listener listener_;
  std::map<std::uint8_t, Entry> nodes_;
  std::uint64_t toggle_errors_ = 0;
};

}  // namespace advee::canopen
