// SPDX-License-Identifier: GPL-2.0
// The passive CANopen master engine: no threads, no I/O, no clock of its own.
// Whoever owns it (the event loop, or a unit test with a virtual bus and a
// manual clock) feeds received frames to handle(), calls poll() when
// next_deadline() has passed, and transmits what comes out of the FrameSender.
#pragma once

#include <array>
#include <cstdint>
#include <functional>
#include <map>
#include <memory>
#include <optional>
#include <set>
#include <unordered_map>
#include <vector>

#include "advee/canopen/clock.hpp"
#include "advee/canopen/emcy.hpp"
#include "advee/canopen/frame.hpp"
#include "advee/canopen/heartbeat.hpp"
#include "advee/canopen/listener_list.hpp"
#include "advee/canopen/nmt.hpp"
#include "advee/canopen/node_guarding.hpp"
#include "advee/canopen/object_dictionary.hpp"
#include "advee/canopen/sdo_client.hpp"
#include "advee/canopen/sdo_server.hpp"
#include "advee/canopen/sync.hpp"
#include "advee/registration.hpp"

namespace advee::canopen {

using advee::Registration;

// Something with its own timers that runs on the master's clock (an axis, a
// drive driver); the owner of the master polls it with the master.
class TimedService {
 public:
  virtual ~TimedService() = default;
  virtual void poll() = 0;
  virtual std::optional<TimePoint> deadline() const = 0;
};

struct MasterConfig {
  std::uint8_t node_id = 0x7F;  // the master's own node-ID (heartbeat producer)
  Duration sdo_timeout = SdoClient::kDefaultTimeout;
  // Zero: the master does not produce heartbeat and stays silent. Otherwise it
  // is a node on the network: boot-up message first, then heartbeats that
  // carry its NMT state (set_nmt_state()).
  Duration heartbeat_period{};
  // The master's own dictionary, served by SDO on 0x600 + node_id while it
  // is a node (heartbeat on): 0x1000, 0x1001, 0x1016:1..kHeartbeatConsumers,
  // 0x1017, 0x1018:1..4.
  std::uint32_t device_type = 0;  // CiA 302: no device profile
  std::array<std::uint32_t, 4> identity{};  // vendor, product, revision, serial
};

// 0x1016 entries of the master's dictionary.
inline constexpr std::uint8_t kHeartbeatConsumers = 8;

class Master {
 public:
  using FrameListener = std::function<void(const CanFrame&)>;

  Master(MasterConfig cfg, FrameSender send, NowFn now, WallClockFn wall = [] { return std::chrono::system_clock::now(); });
  Master(const Master&) = delete;
  Master& operator=(const Master&) = delete;

  void handle(const CanFrame& frame);
  void poll();
  std::optional<TimePoint> next_deadline() const;
  TimePoint now() const { return now_(); }

  // NMT master. node 0 = all nodes.
  void nmt(NmtCommand cmd, std::uint8_t node);

  // One SDO client (and queue) per server node, created on first use.
  SdoClient& sdo(std::uint8_t node);

  HeartbeatConsumer& heartbeat_consumer() { return hb_consumer_; }
  // Guarding events reach the heartbeat listeners (same event types).
  NodeGuarding& node_guarding() { return guarding_; }
  const HeartbeatProducer& heartbeat_producer() const { return hb_producer_; }
  // The master's own heartbeat: the first non-zero period sends the boot-up
  // message (0x700 + node-ID, 0x00) before the first heartbeat; zero stops it.
  void set_heartbeat_period(Duration period);
  Duration heartbeat_period() const { return hb_producer_.period(); }
  // The master's own NMT state (pre-operational after its boot-up), which its
  // heartbeat reports. The owner sets it: operational while it runs the
  // network (CiA 302-2: the NMT master enters operational, then starts the
  // slaves).
  void set_nmt_state(NmtState s);
  NmtState nmt_state() const { return nmt_state_; }
  SyncProducer& sync() { return sync_; }
  // TIME on demand, or periodically from the system wall clock (replace it
  // with set_wall_clock() in tests).
  void send_time(std::chrono::system_clock::time_point t);
  TimeProducer& time_producer() { return time_; }

  // Each registration lasts until its Registration is destroyed or reset();
  // keep it in the object whose `this` the callback captures. It may outlive
  // the master. A callback may end registrations (its own too) while it runs.
  [[nodiscard]] Registration add_heartbeat_listener(std::function<void(const HeartbeatUpdate&)> cb);
  [[nodiscard]] Registration add_emcy_listener(std::function<void(const Emcy&)> cb);
  // Frames with this CAN-ID (a device's TPDO) go to cb.
  [[nodiscard]] Registration subscribe(std::uint32_t can_id, FrameListener cb);
  // Any frame not consumed by a protocol object (monitors, tools).
  void set_fallback_listener(FrameListener cb) { fallback_ = std::move(cb); }
  // Sees every received frame before any protocol object does (monitors).
  void set_observer(FrameListener cb) { observer_ = std::move(cb); }

  // The service is polled by poll() and counted in next_deadline() while the
  // Registration lives (a member of the service).
  [[nodiscard]] Registration attach(TimedService& s);

  // EMCY of the master itself (0x080 + node_id), with the error register
  // (0x1001) it leaves; code 0 is the error reset.
  void send_emcy(std::uint16_t code, std::uint8_t error_register, std::array<std::uint8_t, 5> vendor = {});
  // The master's own faults, as a CiA 301 EMCY producer: an error that
  // becomes active sends its code with the register of every active error
  // (0x1001 follows); one that clears sends the error reset 0x0000 with the
  // register of those still active. Setting a code to the state it has sends
  // nothing. While the master is NMT stopped no EMCY goes out (CiA 301), the
  // register still follows.
  void set_error(std::uint16_t code, bool active);
  bool error_active(std::uint16_t code) const { return active_errors_.contains(code); }
  std::uint8_t error_register() const;
  // The master's own dictionary and its SDO server (tests, tools).
  const ObjectDictionary& dictionary() const { return od_; }
  SdoServer& sdo_server() { return sdo_server_; }

  void send(const CanFrame& f) { send_(f); }
  const MasterConfig& config() const { return cfg_; }

 private:
  void on_heartbeat(const HeartbeatUpdate& u);
  void build_dictionary();

  MasterConfig cfg_;
  FrameSender send_;
  NowFn now_;
  std::map<std::uint8_t, std::unique_ptr<SdoClient>> sdo_;
  HeartbeatConsumer hb_consumer_;
  NodeGuarding guarding_;
  HeartbeatProducer hb_producer_;
  SyncProducer sync_;
  TimeProducer time_;
  ObjectDictionary od_;
  SdoServer sdo_server_;
  std::array<std::uint8_t, kHeartbeatConsumers> consumer_nodes_{};  // the node of each 0x1016 entry
  // Shared with the Registrations' cancel functions (through weak_ptr), so
  // that a Registration may outlive the master.
  struct Registry {
    ListenerList<const HeartbeatUpdate&> heartbeat;
    ListenerList<const Emcy&> emcy;
    std::unordered_map<std::uint32_t, ListenerList<const CanFrame&>> pdo;
    std::map<std::uint64_t, TimedService*> services;
    std::uint64_t next_service = 1;
  };
  template <typename Remove>
  Registration registration(Remove remove);

  std::shared_ptr<Registry> registry_ = std::make_shared<Registry>();
  FrameListener fallback_;
  FrameListener observer_;
  NmtState nmt_state_ = NmtState::kPreOperational;
  bool booted_up_ = false;  // the boot-up message went out
  std::set<std::uint16_t> active_errors_;  // set_error()
};

}  // namespace advee::canopen
