// SPDX-License-Identifier: GPL-2.0
#include "advee/canopen/node_guarding.hpp"

namespace advee::canopen {

NodeGuarding::NodeGuarding(FrameSender send, NowFn now, Listener listener)
    : send_(std::move(send)), now_(std::move(now)), listener_(std::move(listener)) {}

void NodeGuarding::guard(std::uint8_t node, Duration guard_time, std::uint8_t life_time_factor) {
  if (!is_valid_node_id(node)) return;
  if (guard_time.count() <= 0) {
    nodes_.erase(node);
    return;
  }
  Entry& e = nodes_[node];
  e = Entry{};
  e.guard = guard_time;
  e.factor = life_time_factor ? life_time_factor : 1;
  e.next_rtr = now_();
  e.last_valid = now_();
  poll();
}

bool NodeGuarding::handle(const CanFrame& f) {
  if (f.rtr || f.len != 1 || f.id <= cob::kNmtErrorControl || f.id > cob::kNmtErrorControl + 127) return false;
  const auto node = static_cast<std::uint8_t>(f.id - cob::kNmtErrorControl);
  auto it = nodes_.find(node);
  if (it == nodes_.end()) return false;
  Entry& e = it->second;
  const bool toggle = f.data[0] & 0x80;
  const auto state = static_cast<NmtState>(f.data[0] & 0x7F);
  // Boot-up (0x00) restarts the toggle sequence; otherwise it must alternate.
  if (state != NmtState::kBootUp && e.last_toggle && *e.last_toggle == toggle) {
    ++toggle_errors_;
    return true;
  }
  e.last_toggle = state == NmtState::kBootUp ? std::nullopt : std::optional<bool>(toggle);
  e.last_valid = now_();
  const bool was_lost = e.lost;
  const NmtState previous = e.state;
  e.lost = false;
  e.state = state;
  if (listener_) {
    if (was_lost) listener_({node, HeartbeatEvent::kResumed, state});
    if (state == NmtState::kBootUp)
      listener_({node, HeartbeatEvent::kBootUp, state});
    else if (state != previous)
      listener_({node, HeartbeatEvent::kStateChanged, state});
  }
  return true;
}

void NodeGuarding::poll() {
  const TimePoint now = now_();
  for (auto& [node, e] : nodes_) {
    if (now >= e.next_rtr) {
      CanFrame rtr;
      rtr.id = cob::kNmtErrorControl + node;
      rtr.rtr = true;
      rtr.len = 1;
      send_(rtr);
      e.next_rtr += e.guard;
      if (e.next_rtr <= now) e.next_rtr = now + e.guard;
    }
    if (!e.lost && now - e.last_valid >= e.guard * e.factor) {
      e.lost = true;
      if (listener_) listener_({node, HeartbeatEvent::kLost, e.state});
    }
  }
}

std::optional<TimePoint> NodeGuarding::deadline() const {
  std::optional<TimePoint> d;
  for (const auto& [node, e] : nodes_) {
    TimePoint t = e.next_rtr;
    if (!e.lost && e.last_valid + e.guard * e.factor < t) t = e.last_valid + e.guard * e.factor;
    if (!d || t < *d) d = t;
  }
  return d;
}

bool NodeGuarding::lost(std::uint8_t node) const {
  auto it = nodes_.find(node);
  return it != nodes_.end() && it->second.lost;
}

}  // namespace advee::canopen
