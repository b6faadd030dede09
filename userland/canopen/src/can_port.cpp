// SPDX-License-Identifier: GPL-2.0
#include "advee/canopen/can_port.hpp"

#include <sys/epoll.h>

namespace advee::canopen {

namespace {
constexpr auto kFirstBackoff = std::chrono::milliseconds(1);
constexpr auto kMaxBackoff = std::chrono::milliseconds(32);
constexpr std::size_t kMaxReadsPerWakeup = 256;  // let timers run under a flood
constexpr std::size_t kRxBatch = 64;             // frames per recvmmsg()
constexpr std::size_t kMaxTxQueue = 4096;        // ~0.5 s of a saturated 1 Mbit/s bus
}  // namespace

CanPort::CanPort(EventLoop& loop, CanSocket socket, FrameHandler on_frame, ErrorHandler on_error)
    : loop_(loop), socket_(std::move(socket)), on_frame_(std::move(on_frame)), on_error_(std::move(on_error)) {
  loop_.add_fd(socket_.fd(), EPOLLIN, [this](std::uint32_t) { on_readable(); });
  loop_.add_timer_source([this] { return retry_at_; },
                         [this] {
                           if (retry_at_ && SteadyClock::now() >= *retry_at_) {
                             retry_at_.reset();
                             flush();
                           }
                         });
}

CanPort::~CanPort() { loop_.remove_fd(socket_.fd()); }

void CanPort::send(const CanFrame& f) {
  if (txq_.size() >= kMaxTxQueue) {
    // Bus-off or a stuck queue: the oldest frame is the stalest command.
    txq_.pop_front();
    ++stats_.tx_dropped;
  }
  txq_.push_back(f);
  if (!retry_at_) flush();
}

void CanPort::flush() {
  if (state_ == CanControllerState::kBusOff) return;
  while (!txq_.empty()) {
    switch (socket_.send(txq_.front())) {
      case CanSocket::SendStatus::kSent:
        ++stats_.tx_frames;
        txq_.pop_front();
        backoff_ = {};
        break;
      case CanSocket::SendStatus::kRetryLater:
        ++stats_.tx_retries;
        backoff_ = backoff_.count() ? std::min<Duration>(backoff_ * 2, kMaxBackoff) : Duration(kFirstBackoff);
        retry_at_ = SteadyClock::now() + backoff_;
        return;
      case CanSocket::SendStatus::kFailed:
        // Interface down or similar: the frame is lost; report and go on.
        ++stats_.tx_failed;
        txq_.pop_front();
        break;
    }
  }
}

void CanPort::on_readable() {
  for (std::size_t read = 0; read < kMaxReadsPerWakeup;) {
    rx_batch_.clear();
    const std::size_t n = socket_.receive_batch(rx_batch_, kRxBatch);
    read += n;
    for (const auto& r : rx_batch_) dispatch(r);
    if (n < kRxBatch) break;  // drained
  }
  stats_.rx_dropped = socket_.dropped();
}

void CanPort::dispatch(const CanSocket::Received& r) {
  if (auto* f = std::get_if<CanFrame>(&r)) {
    ++stats_.rx_frames;
    if (state_ == CanControllerState::kBusOff) {
      state_ = CanControllerState::kErrorActive;  // traffic again: the controller is back
      flush();
    }
    on_frame_(*f);
    return;
  }
  ++stats_.error_frames;
  const CanErrorInfo& e = std::get<CanSocket::Error>(r).info;
  if (e.state) {
    const bool was_off = state_ == CanControllerState::kBusOff;
    state_ = *e.state;
    if (was_off && state_ != CanControllerState::kBusOff) flush();
  }
  if (on_error_) on_error_(e);
}

}  // namespace advee::canopen
