// SPDX-License-Identifier: GPL-2.0
#include "advee/canopen/heartbeat.hpp"

namespace advee::canopen {

HeartbeatConsumer::HeartbeatConsumer(NowFn now, Listener listener)
    : now_(std::move(now)), listener_(std::move(listener)) {}

void HeartbeatConsumer::monitor(std::uint8_t node, Duration timeout) {
  if (!is_valid_node_id(node)) return;
  nodes_[node].timeout = timeout;
}

bool HeartbeatConsumer::handle(const CanFrame& f) {
  if (f.rtr || f.id <= cob::kNmtErrorControl || f.id > cob::kNmtErrorControl + 127) return false;
  if (f.len != 1) return true;  // node-guarding replies etc. carry the toggle bit; not a heartbeat
  const auto node = static_cast<std::uint8_t>(f.id - cob::kNmtErrorControl);
  Entry& e = nodes_[node];
  const auto state = static_cast<NmtState>(f.data[0] & 0x7F);
  const bool was_lost = e.lost;
  const NmtState previous = e.state;
  e.last_seen = now_();
  e.lost = false;
  e.state = state;
  if (!listener_) return true;
  if (was_lost) listener_({node, HeartbeatEvent::kResumed, state});
  if (state == NmtState::kBootUp)
    listener_({node, HeartbeatEvent::kBootUp, state});
  else if (state != previous)
    listener_({node, HeartbeatEvent::kStateChanged, state});
  return true;
}

void HeartbeatConsumer::poll() {
  const TimePoint now = now_();
  for (std::size_t n = 1; n < nodes_.size(); ++n) {
    Entry& e = nodes_[n];
    if (e.timeout.count() == 0 || !e.last_seen || e.lost) continue;
    if (now - *e.last_seen >= e.timeout) {
      e.lost = true;
      if (listener_) listener_({static_cast<std::uint8_t>(n), HeartbeatEvent::kLost, e.state});
    }
  }
}

std::optional<TimePoint> HeartbeatConsumer::deadline() const {
  std::optional<TimePoint> d;
  for (const Entry& e : nodes_) {
    if (e.timeout.count() == 0 || !e.last_seen || e.lost) continue;
    const TimePoint t = *e.last_seen + e.timeout;
    if (!d || t < *d) d = t;
  }
  return d;
}

NmtState HeartbeatConsumer::state(std::uint8_t node) const {
  return node < nodes_.size() ? nodes_[node].state : NmtState::kUnknown;
}

bool HeartbeatConsumer::lost(std::uint8_t node) const { return node < nodes_.size() && nodes_[node].lost; }

HeartbeatProducer::HeartbeatProducer(std::uint8_t node, FrameSender send, NowFn now)
    : node_(node), send_(std::move(send)), now_(std::move(now)) {}

void HeartbeatProducer::set_period(Duration period) {
  period_ = period;
  if (period_.count() == 0) return;
  next_ = now_();
  poll();
}

void HeartbeatProducer::poll() {
  if (period_.count() == 0) return;
  const TimePoint now = now_();
  if (now < next_) return;
  send_(heartbeat_frame(node_, state_));
  next_ = next_period(next_, now, period_);
}

std::optional<TimePoint> HeartbeatProducer::deadline() const {
  if (period_.count() == 0) return std::nullopt;
  return next_;
}

}  // namespace advee::canopen
