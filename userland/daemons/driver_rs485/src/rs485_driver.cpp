// SPDX-License-Identifier: GPL-2.0
#include "advee/driver_rs485/rs485_driver.hpp"

#include <algorithm>
#include <lcm/lcm-cpp.hpp>

#include "advee/driver_rs485/messages.hpp"
#include "advee/module/time.hpp"
#include "advee/msgs/channels.hpp"

namespace advee::driver_rs485 {

using namespace std::chrono_literals;

Rs485Driver::Rs485Driver(module::Module& m, Rs485Config cfg, rs485::Transport& bus, NodeStatusFn node_status)
    : m_(m), cfg_(std::move(cfg)), node_status_(std::move(node_status)) {
  // Per-call options equal to the bus defaults: they also hold on a
  // transport without bus configuration (FakeTransport, a shared bus).
  call_ = rs485::CallOptions(cfg_.bus.config.timeout, cfg_.bus.config.retries);
  const auto period = std::chrono::nanoseconds(static_cast<std::int64_t>(1e9 / cfg_.rate_hz));
  for (const auto& b : cfg_.sd1)
    sd1_.push_back(std::make_unique<Sd1Node>(Sd1Node{&b, rs485::Sd1(bus, b.address),
                                                     NodeHealth(m_.errors(), b.name, b.address)}));
  if (cfg_.so1) {
    so1_.emplace(bus, cfg_.so1->address);
    so1_health_.emplace(m_.errors(), "odometry", cfg_.so1->address);
    odo_.emplace(cfg_.so1->geometry);
    // The board counts on through any gap, so an interval may span missed
    // polls; only from this gap on could the counters have wrapped unseen.
    max_odo_gap_ = unambiguous_tick_gap(cfg_.so1->geometry, cfg_.so1->width, cfg_.so1->max_speed_mps);
  }
  if (cfg_.sbs1) {
    sbs1_.emplace(bus, cfg_.sbs1->address);
    sbs1_health_.emplace(m_.errors(), "beacons", cfg_.sbs1->address);
    if (!cfg_.sbs1->beacon_ids.empty()) {
      beacon_ids_ = cfg_.sbs1->beacon_ids;
      ids_pending_ = true;
    }
    beacons_sub_.emplace(m_.lcm(), std::string(msgs::kDataActiveBeacons.name),
                         [this](const lowlevel::data_active_beacons_t& msg) { on_active_beacons(msg); });
  }
  m_.on_state_change([this](module::State, module::State to) {
    if (to == module::State::Run) last_counts_.reset();  // the pause is no odometry interval
  });
  m_.every(period, [this] { poll(); });
}

void Rs485Driver::on_active_beacons(const lowlevel::data_active_beacons_t& m) {
  const auto* msg = &m;
  std::vector<std::uint8_t> ids;
  for (auto id : msg->id) {
    if (id < 0 || id > 255) {
      m_.errors().report(module::Severity::Warning, module::ErrorType::Unknown, kErrBadBeaconId,
                         "LL_DATA_ACTIVE_BEACONS from " + msg->module + ": beacon id " + std::to_string(id) +
                             " out of 0..255 ignored");
      continue;
    }
    ids.push_back(static_cast<std::uint8_t>(id));
  }
  if (ids.size() > rs485::sbs1::kMaxBeaconIds) ids.resize(rs485::sbs1::kMaxBeaconIds);
  beacon_ids_ = std::move(ids);
  ids_pending_ = true;  // applied before the next GET_BEACON_DATA
}

void Rs485Driver::poll() {
  if (!sd1_.empty()) poll_sd1s();
  if (so1_) poll_so1();
  if (sbs1_) poll_sbs1();
}

void Rs485Driver::poll_sd1s() {
  lowlevel::data_srfs_t msg{};
  bool any = false;
  for (auto& n : sd1_) {
    if (!n->health.may_poll(node_status_)) continue;
    auto d = n->dev.distances(call_);
    n->health.record("GET_BOTH", d ? std::error_code() : d.error(), node_status_);
    if (!d) continue;
    append_ranges(*n->cfg, *d, msg);
    any = true;
  }
  if (!any) return;  // nothing measured: no message rather than an empty one
  msg.utime = module::utime_now();
  msg.module = m_.name();
  m_.lcm().publish(std::string(msgs::kDataSrfs.name), &msg);
}

void Rs485Driver::poll_so1() {
  if (!so1_health_->may_poll(node_status_)) return;
  auto raw = so1_->raw_ticks(cfg_.so1->width, call_);
  so1_health_->record("GET_TICKS", raw ? std::error_code() : raw.error(), node_status_);
  if (!raw) return;
  const auto now = m_.timers().now();  // the loop's clock (a manual one in tests)
  const bool ambiguous = last_counts_ && now - last_counts_at_ >= max_odo_gap_;
  if (ambiguous)
    m_.errors().report(module::Severity::Warning, module::ErrorType::Device, kErrOdoGap,
                       "odometry: " + std::to_string(std::chrono::duration<double>(now - last_counts_at_).count()) +
                           " s since the last BR-SO1 reading, the counters may have wrapped: its ticks are dropped");
  if (!last_counts_ || ambiguous) {
    ticks_.reset();
    last_counts_ = ticks_.update(*raw);  // a new baseline, no interval yet
    last_counts_at_ = now;
    return;
  }
  const auto counts = ticks_.update(*raw);
  const double dt = std::chrono::duration<double>(now - last_counts_at_).count();
  auto msg = odo_message(*odo_, counts.left - last_counts_->left, counts.right - last_counts_->right, dt);
  last_counts_ = counts;
  last_counts_at_ = now;
  msg.utime = module::utime_now();
  msg.module = m_.name();
  m_.lcm().publish(std::string(msgs::kDataOdo.name), &msg);
}

void Rs485Driver::poll_sbs1() {
  if (!sbs1_health_->may_poll(node_status_)) return;
  const auto now = m_.timers().now();  // the loop's clock (a manual one in tests)
  if (beacon_ids_ && (ids_pending_ || now - ids_sent_at_ >= cfg_.sbs1->resend_ids)) {
    const auto ec = sbs1_->set_beacon_ids(*beacon_ids_, call_);
    sbs1_health_->record("SET_BEACON_IDS", ec, node_status_);
    if (ec) return;  // stays pending; the next round tries again
    ids_pending_ = false;
    ids_sent_at_ = now;
  }
  auto seen = sbs1_->beacons(call_);
  sbs1_health_->record("GET_BEACON_DATA", seen ? std::error_code() : seen.error(), node_status_);
  if (!seen) return;
  auto msg = beacons_message(*seen);
  msg.utime = module::utime_now();
  msg.module = m_.name();
  m_.lcm().publish(std::string(msgs::kDataBeacons.name), &msg);
}

}  // namespace advee::driver_rs485
