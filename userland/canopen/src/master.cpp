// SPDX-License-Identifier: GPL-2.0
#include "advee/canopen/master.hpp"

#include <algorithm>

namespace advee::canopen {

Master::Master(MasterConfig cfg, FrameSender send, NowFn now, WallClockFn wall)
    : cfg_(cfg),
      send_(std::move(send)),
      now_(std::move(now)),
      hb_consumer_(now_, [this](const HeartbeatUpdate& u) { on_heartbeat(u); }),
      guarding_(send_, now_, [this](const HeartbeatUpdate& u) { on_heartbeat(u); }),
      hb_producer_(cfg_.node_id, send_, now_),
      sync_(send_, now_),
      time_(send_, now_, std::move(wall)) {
  hb_producer_.set_state(nmt_state_);
  set_heartbeat_period(cfg_.heartbeat_period);
}

void Master::set_heartbeat_period(Duration period) {
  if (period.count() > 0 && !booted_up_) {
    booted_up_ = true;
    send_(heartbeat_frame(cfg_.node_id, NmtState::kBootUp));
  }
  hb_producer_.set_period(period);
}

void Master::set_nmt_state(NmtState s) {
  nmt_state_ = s;
  hb_producer_.set_state(s);
}

void Master::handle(const CanFrame& f) {
  if (observer_) observer_(f);
  if (f.id >= cob::kSdoTx + 1 && f.id <= cob::kSdoTx + 127) {
    auto it = sdo_.find(static_cast<std::uint8_t>(f.id - cob::kSdoTx));
    if (it != sdo_.end() && it->second->handle(f)) return;
  } else if (guarding_.handle(f) || hb_consumer_.handle(f)) {
    return;
  } else if (auto e = decode_emcy(f)) {
    auto listeners = emcy_listeners_;  // a listener may remove itself
    for (auto& [id, cb] : listeners) cb(*e);
    return;
  }
  auto it = pdo_listeners_.find(f.id);
  if (it != pdo_listeners_.end() && !f.rtr && !it->second.empty()) {
    // Copy: a listener may unsubscribe while we iterate.
    auto subs = it->second;
    for (auto& s : subs) s.cb(f);
    return;
  }
  if (fallback_) fallback_(f);
}

void Master::on_heartbeat(const HeartbeatUpdate& u) {
  // A boot-up does not cancel the node's SDO transfers: which of our requests
  // reached it before it rebooted cannot be told from here (a request sent
  // while its boot-up waited in our receive queue did), and some nodes repeat
  // their boot-up without resetting. A transfer the node lost ends with its
  // abort or the step timeout; the drivers re-boot the node on this event.
  auto listeners = hb_listeners_;  // a listener may remove itself
  for (auto& [id, cb] : listeners) cb(u);
}

void Master::poll() {
  for (auto& [node, c] : sdo_) c->poll();
  hb_consumer_.poll();
  guarding_.poll();
  hb_producer_.poll();
  sync_.poll();
  time_.poll();
  // Copy: a service may detach another one from inside poll().
  auto services = services_;
  for (TimedService* s : services) s->poll();
}

std::optional<TimePoint> Master::next_deadline() const {
  std::optional<TimePoint> d;
  auto take = [&d](std::optional<TimePoint> t) {
    if (t && (!d || *t < *d)) d = t;
  };
  for (auto& [node, c] : sdo_) take(c->deadline());
  take(hb_consumer_.deadline());
  take(guarding_.deadline());
  take(hb_producer_.deadline());
  take(sync_.deadline());
  take(time_.deadline());
  for (const TimedService* s : services_) take(s->deadline());
  return d;
}

void Master::nmt(NmtCommand cmd, std::uint8_t node) { send_(nmt_command_frame(cmd, node)); }

SdoClient& Master::sdo(std::uint8_t node) {
  auto& c = sdo_[node];
  if (!c) c = std::make_unique<SdoClient>(node, send_, now_, cfg_.sdo_timeout);
  return *c;
}

void Master::send_time(std::chrono::system_clock::time_point t) { send_(time_of_day_frame(t)); }

Master::ListenerId Master::add_heartbeat_listener(std::function<void(const HeartbeatUpdate&)> cb) {
  hb_listeners_.emplace_back(next_id_, std::move(cb));
  return next_id_++;
}

Master::ListenerId Master::add_emcy_listener(std::function<void(const Emcy&)> cb) {
  emcy_listeners_.emplace_back(next_id_, std::move(cb));
  return next_id_++;
}

void Master::remove_listener(ListenerId id) {
  std::erase_if(hb_listeners_, [id](const auto& l) { return l.first == id; });
  std::erase_if(emcy_listeners_, [id](const auto& l) { return l.first == id; });
  unsubscribe(id);
}

Master::ListenerId Master::subscribe(std::uint32_t can_id, FrameListener cb) {
  const ListenerId id = next_id_++;
  pdo_listeners_[can_id].push_back({id, std::move(cb)});
  return id;
}

void Master::unsubscribe(ListenerId id) {
  for (auto& [can_id, subs] : pdo_listeners_)
    std::erase_if(subs, [id](const Subscription& s) { return s.id == id; });
}

}  // namespace advee::canopen
