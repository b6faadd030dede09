// SPDX-License-Identifier: GPL-2.0
// Heartbeat consumer (object 0x1016 semantics: a node is monitored from its
// first heartbeat on, and is lost when none arrives within its consumer time)
// and heartbeat producer (object 0x1017). Both passive.
#pragma once

#include <array>
#include <cstdint>
#include <functional>
#include <optional>

#include "advee/canopen/clock.hpp"
#include "advee/canopen/frame.hpp"
#include "advee/canopen/nmt.hpp"

namespace advee::canopen {

enum class HeartbeatEvent {
  kBootUp,        // boot-up message: the node (re)started and lost its volatile configuration
  kStateChanged,  // reported NMT state differs from the previous one
  kLost,          // consumer time elapsed without a heartbeat
  kResumed,       // heartbeat seen again after kLost
};

struct HeartbeatUpdate {
  std::uint8_t node = 0;
  HeartbeatEvent event = HeartbeatEvent::kStateChanged;
  NmtState state = NmtState::kUnknown;
};

class HeartbeatConsumer {
 public:
  using Listener = std::function<void(const HeartbeatUpdate&)>;

  HeartbeatConsumer(NowFn now, Listener listener);

  // timeout zero stops monitoring (the state is still tracked).
  void monitor(std::uint8_t node, Duration timeout);
  // True if the frame was a heartbeat / boot-up (0x701..0x77F, DLC 1).
  bool handle(const CanFrame& frame);
  void poll();
  std::optional<TimePoint> deadline() const;

  NmtState state(std::uint8_t node) const;
  bool lost(std::uint8_t node) const;

 private:
  struct Entry {
    Duration timeout{};
    std::optional<TimePoint> last_seen;
    NmtState state = NmtState::kUnknown;
    bool lost = false;
  };
  NowFn now_;
  Listener listener_;
  std::array<Entry, 128> nodes_{};
};

class HeartbeatProducer {
 public:
  HeartbeatProducer(std::uint8_t node, FrameSender send, NowFn now);

  // Zero disables. Enabling sends one heartbeat at once, so consumers that were
  // just configured see the producer immediately.
  void set_period(Duration period);
  void set_state(NmtState s) { state_ = s; }
  void poll();
  std::optional<TimePoint> deadline() const;
  Duration period() const { return period_; }

 private:
  std::uint8_t node_;
  FrameSender send_;
  NowFn now_;
  Duration period_{};
  NmtState state_ = NmtState::kPreOperational;
  TimePoint next_{};
};

}  // namespace advee::canopen
