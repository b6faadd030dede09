// SPDX-License-Identifier: GPL-2.0
// A CanSocket on an EventLoop: reads every pending frame on readiness, keeps
// a transmit queue that backs off on ENOBUFS (1 ms doubling to 32 ms) instead
// of dropping, holds transmission while the controller is bus-off (until the
// kernel's restart-ms restarts it or any frame is received), and counts. The
// queue is bounded (4096 frames); when full the oldest frame goes.
#pragma once

#include <cstdint>
#include <deque>
#include <functional>
#include <optional>
#include <vector>

#include "advee/canopen/event_loop.hpp"
#include "advee/canopen/socketcan.hpp"

namespace advee::canopen {

struct CanPortStats {
  std::uint64_t rx_frames = 0;
  std::uint64_t tx_frames = 0;
  std::uint64_t tx_retries = 0;  // ENOBUFS back-offs
  std::uint64_t tx_failed = 0;
  std::uint64_t tx_dropped = 0;  // oldest frames dropped from a full transmit queue
  std::uint64_t error_frames = 0;
  std::uint32_t rx_dropped = 0;  // kernel drops for this socket (SO_RXQ_OVFL)
};

class CanPort {
 public:
  using FrameHandler = std::function<void(const CanFrame&)>;
  using ErrorHandler = std::function<void(const CanErrorInfo&)>;

  CanPort(EventLoop& loop, CanSocket socket, FrameHandler on_frame, ErrorHandler on_error = nullptr);
  ~CanPort();
  CanPort(const CanPort&) = delete;
  CanPort& operator=(const CanPort&) = delete;

  void send(const CanFrame& f);  // loop thread only
  FrameSender sender() {
    return [this](const CanFrame& f) { send(f); };
  }
  const CanPortStats& stats() const { return stats_; }
  CanControllerState controller_state() const { return state_; }
  std::size_t tx_pending() const { return txq_.size(); }

 private:
  void on_readable();
  void dispatch(const CanSocket::Received& r);
  void flush();

  EventLoop& loop_;
  CanSocket socket_;
  FrameHandler on_frame_;
  ErrorHandler on_error_;
  std::deque<CanFrame> txq_;
  std::optional<TimePoint> retry_at_;
  Duration backoff_{};
  CanControllerState state_ = CanControllerState::kErrorActive;
  CanPortStats stats_;
  std::vector<CanSocket::Received> rx_batch_;
};

}  // namespace advee::canopen
