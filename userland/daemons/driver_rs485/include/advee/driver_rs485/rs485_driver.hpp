// SPDX-License-Identifier: GPL-2.0
// driver_rs485 (thesis 5.4, 5.5): polls the boards of one bus at `rate_hz`
// in RUN (PAUSE stops the polling) and publishes LL_DATA_SRFS (BR-SD1),
// LL_DATA_ODO (BR-SO1) and LL_DATA_BEACONS (BR-SBS1, whose beacon ids come
// from LL_DATA_ACTIVE_BEACONS). Works on any rs485::Transport, so the unit
// tests drive it with FakeTransport.
#pragma once

#include <chrono>
#include <memory>
#include <optional>
#include <vector>

#include "advee/driver_rs485/config.hpp"
#include "advee/driver_rs485/odometry.hpp"
#include "advee/module/module.hpp"
#include "advee/rs485/devices/sbs1.hpp"
#include "advee/rs485/devices/sd1.hpp"
#include "advee/module/subscription.hpp"
#include "advee/rs485_daemon/node_health.hpp"
#include "advee/rs485/devices/so1.hpp"
#include "lowlevel/data_active_beacons_t.hpp"

namespace advee::driver_rs485 {

// Exit details (module::ExitKind::Device + n).
inline constexpr int kExitNoBus = 1;  // the bus cannot be opened or configured

// Error numbers on CM_DATA_ERROR besides those of rs485_daemon::NodeHealth (1-4).
inline constexpr int kErrBadBeaconId = 5;  // LL_DATA_ACTIVE_BEACONS id out of 0..255 (warning)
inline constexpr int kErrOdoGap = 6;       // odometry ticks of a too long gap dropped (warning)

using rs485_daemon::NodeHealth;
using rs485_daemon::NodeStatusFn;

class Rs485Driver {
 public:
  // Registers the periodic poll and the LL_DATA_ACTIVE_BEACONS handler on `m`.
  Rs485Driver(module::Module& m, Rs485Config cfg, rs485::Transport& bus, NodeStatusFn node_status = {});
  Rs485Driver(const Rs485Driver&) = delete;
  Rs485Driver& operator=(const Rs485Driver&) = delete;

  void poll();  // one round over every board (the module loop calls it in RUN)

 private:
  struct Sd1Node {
    const Sd1Board* cfg;
    rs485::Sd1 dev;
    NodeHealth health;
  };
  void poll_sd1s();
  void poll_so1();
  void poll_sbs1();
  void on_active_beacons(const lowlevel::data_active_beacons_t& msg);

  module::Module& m_;
  Rs485Config cfg_;
  NodeStatusFn node_status_;
  rs485::CallOptions call_;
  std::vector<std::unique_ptr<Sd1Node>> sd1_;

  std::optional<rs485::So1> so1_;
  std::optional<NodeHealth> so1_health_;
  std::optional<AckermannOdometry> odo_;
  rs485::TickAccumulator ticks_;
  std::optional<rs485::So1Counts> last_counts_;
  std::chrono::steady_clock::time_point last_counts_at_;
  std::chrono::nanoseconds max_odo_gap_;

  std::optional<rs485::Sbs1> sbs1_;
  std::optional<NodeHealth> sbs1_health_;
  std::optional<std::vector<std::uint8_t>> beacon_ids_;  // nullopt: none known yet
  bool ids_pending_ = false;
  std::chrono::steady_clock::time_point ids_sent_at_;
  std::optional<module::Subscription<lowlevel::data_active_beacons_t>> beacons_sub_;
};

}  // namespace advee::driver_rs485
