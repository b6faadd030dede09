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
      time_(send_, now_, std::move(wall)),
      sdo_server_(cfg_.node_id, od_, send_, now_) {
  build_dictionary();
  hb_producer_.set_state(nmt_state_);
  set_heartbeat_period(cfg_.heartbeat_period);
}

// CiA 301 communication objects of the master as a node. Writes to 0x1016
// and 0x1017 take effect at once, as on any node.
void Master::build_dictionary() {
  using A = Access;
  od_.add<std::uint32_t>(0x1000, 0, cfg_.device_type, A::kReadOnly);
  od_.add<std::uint8_t>(0x1001, 0, 0, A::kReadOnly);
  od_.add<std::uint8_t>(0x1016, 0, kHeartbeatConsumers, A::kReadOnly);
  for (std::uint8_t i = 1; i <= kHeartbeatConsumers; ++i) od_.add<std::uint32_t>(0x1016, i, 0);
  od_.add<std::uint16_t>(0x1017, 0, static_cast<std::uint16_t>(
                                        std::chrono::duration_cast<std::chrono::milliseconds>(cfg_.heartbeat_period).count()));
  od_.add<std::uint8_t>(0x1018, 0, 4, A::kReadOnly);
  for (std::uint8_t i = 1; i <= 4; ++i) od_.add<std::uint32_t>(0x1018, i, cfg_.identity[i - 1], A::kReadOnly);
  // 0x1016:n = node-ID in bits 16..23, consumer time in ms in bits 0..15.
  // CiA 301: two entries for one node with non-zero times are refused.
  od_.set_validator(0x1016, [this](std::uint8_t sub, std::span<const std::uint8_t> data) {
    const auto v = load_le<std::uint32_t>(data);
    const auto node = (v >> 16) & 0xFF;
    if (v & 0xFF000000u || node > 127) return SdoAbort::kInvalidValue;
    if (node == 0 || (v & 0xFFFF) == 0) return SdoAbort::kNone;
    for (std::uint8_t i = 1; i <= kHeartbeatConsumers; ++i) {
      const auto other = od_.get<std::uint32_t>(0x1016, i);
      if (i != sub && ((other >> 16) & 0xFF) == node && (other & 0xFFFF) != 0) return SdoAbort::kParamIncompatible;
    }
    return SdoAbort::kNone;
  });
  // An entry's node stops being watched when the entry names another one
  // (nodes the drivers watch by their own monitor() calls stay watched).
  od_.on_write(0x1016, [this](std::uint8_t sub) {
    const auto v = od_.get<std::uint32_t>(0x1016, sub);
    std::uint8_t& watched = consumer_nodes_[sub - 1];
    if (watched != 0) hb_consumer_.monitor(watched, Duration{});
    watched = static_cast<std::uint8_t>((v >> 16) & 0x7F);
    if (watched != 0) hb_consumer_.monitor(watched, std::chrono::milliseconds(v & 0xFFFF));
  });
  od_.on_write(0x1017, [this](std::uint8_t) {
    hb_producer_.set_period(std::chrono::milliseconds(od_.get<std::uint16_t>(0x1017)));
  });
}

void Master::send_emcy(std::uint16_t code, std::uint8_t error_register, std::array<std::uint8_t, 5> vendor) {
  od_.set<std::uint8_t>(0x1001, 0, error_register);
  send_(emcy_frame({cfg_.node_id, code, error_register, vendor}));
}

std::uint8_t Master::error_register() const {
  std::uint8_t r = 0;
  for (const auto code : active_errors_) r |= error_register_bits(code);
  return r;
}

void Master::set_error(std::uint16_t code, bool active) {
  if (code == 0 || active == error_active(code)) return;
  if (active)
    active_errors_.insert(code);
  else
    active_errors_.erase(code);
  const std::uint8_t reg = error_register();
  od_.set<std::uint8_t>(0x1001, 0, reg);
  if (nmt_state_ != NmtState::kStopped) send_(emcy_frame({cfg_.node_id, active ? code : std::uint16_t{0}, reg, {}}));
}

void Master::set_heartbeat_period(Duration period) {
  if (period.count() > 0 && !booted_up_) {
    booted_up_ = true;
    send_(heartbeat_frame(cfg_.node_id, NmtState::kBootUp));
  }
  hb_producer_.set_period(period);
  od_.set<std::uint16_t>(0x1017, 0,
                         static_cast<std::uint16_t>(std::chrono::duration_cast<std::chrono::milliseconds>(period).count()));
}

void Master::set_nmt_state(NmtState s) {
  nmt_state_ = s;
  hb_producer_.set_state(s);
}

void Master::handle(const CanFrame& f) {
  if (observer_) observer_(f);
  // Requests to the master's own dictionary, while it is a node.
  if (booted_up_ && sdo_server_.handle(f)) return;
  if (f.id >= cob::kSdoTx + 1 && f.id <= cob::kSdoTx + 127) {
    auto it = sdo_.find(static_cast<std::uint8_t>(f.id - cob::kSdoTx));
    if (it != sdo_.end() && it->second->handle(f)) return;
  } else if (guarding_.handle(f) || hb_consumer_.handle(f)) {
    return;
  } else if (auto e = decode_emcy(f)) {
    registry_->emcy.call(*e);
    return;
  }
  auto it = registry_->pdo.find(f.id);
  if (it != registry_->pdo.end() && !f.rtr && !it->second.empty()) {
    it->second.call(f);
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
  registry_->heartbeat.call(u);
}

void Master::poll() {
  for (auto& [node, c] : sdo_) c->poll();
  hb_consumer_.poll();
  guarding_.poll();
  hb_producer_.poll();
  sync_.poll();
  time_.poll();
  sdo_server_.poll();
  // A service may end another one's registration (and destroy it) from
  // inside poll(): each is looked up again before it is polled.
  std::vector<std::uint64_t> ids;
  for (const auto& [id, s] : registry_->services) ids.push_back(id);
  for (std::uint64_t id : ids)
    if (auto it = registry_->services.find(id); it != registry_->services.end()) it->second->poll();
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
  take(sdo_server_.deadline());
  for (const auto& [id, s] : registry_->services) take(s->deadline());
  return d;
}

void Master::nmt(NmtCommand cmd, std::uint8_t node) { send_(nmt_command_frame(cmd, node)); }

SdoClient& Master::sdo(std::uint8_t node) {
  auto& c = sdo_[node];
  if (!c) c = std::make_unique<SdoClient>(node, send_, now_, cfg_.sdo_timeout);
  return *c;
}

void Master::send_time(std::chrono::system_clock::time_point t) { send_(time_of_day_frame(t)); }

template <typename Remove>
Registration Master::registration(Remove remove) {
  return Registration([weak = std::weak_ptr<Registry>(registry_), remove] {
    if (auto r = weak.lock()) remove(*r);
  });
}

Registration Master::add_heartbeat_listener(std::function<void(const HeartbeatUpdate&)> cb) {
  const auto id = registry_->heartbeat.add(std::move(cb));
  return registration([id](Registry& r) { r.heartbeat.remove(id); });
}

Registration Master::add_emcy_listener(std::function<void(const Emcy&)> cb) {
  const auto id = registry_->emcy.add(std::move(cb));
  return registration([id](Registry& r) { r.emcy.remove(id); });
}

Registration Master::subscribe(std::uint32_t can_id, FrameListener cb) {
  const auto id = registry_->pdo[can_id].add(std::move(cb));
  return registration([can_id, id](Registry& r) { r.pdo[can_id].remove(id); });
}

Registration Master::attach(TimedService& s) {
  const auto id = registry_->next_service++;
  registry_->services.emplace(id, &s);
  return registration([id](Registry& r) { r.services.erase(id); });
}

}  // namespace advee::canopen
