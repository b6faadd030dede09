// SPDX-License-Identifier: GPL-2.0
// Rs485Driver on FakeTransport and LCM memq://: what the boards answer
// arrives in LL_DATA_SRFS / LL_DATA_ODO / LL_DATA_BEACONS fields; failures
// and node states are reported once; an off node is not polled until reset;
// LL_DATA_ACTIVE_BEACONS reaches the scanner; PAUSE stops the polling.
#include <gtest/gtest.h>

#include <atomic>
#include <lcm/lcm-cpp.hpp>
#include <memory>

#include "advee/module/subscription.hpp"
#include "advee/module/manual_loop.hpp"
#include <map>
#include <mutex>
#include <numbers>

#include "advee/driver_rs485/messages.hpp"
#include "advee/driver_rs485/rs485_driver.hpp"
#include "advee/rs485/fake_transport.hpp"
#include "common/error_t.hpp"
#include "lowlevel/data_active_beacons_t.hpp"

using namespace advee;
using namespace advee::driver_rs485;
using namespace std::chrono_literals;
using rs485::FakeTransport;

namespace {

using rs485_daemon::kErrOff;
using rs485_daemon::kErrPassive;
using rs485_daemon::kErrRecovered;
using rs485_daemon::kErrTransaction;

// The modules run on a manual clock: `d` of module time in 1 ms steps, each
// followed by the loop passes that handle what became ready (memq delivers
// on the pass after a publish). No wall-clock wait: the fake transport
// answers synchronously, and the driver measures odometry intervals on the
// module's clock, so they are exact.
module::ManualTimers clock_;
void spin(module::Module& m, std::chrono::milliseconds d) { module::run_manual(m, clock_, d); }

struct Rx {
  std::vector<lowlevel::data_srfs_t> srfs;
  std::vector<lowlevel::data_odo_t> odo;
  std::vector<lowlevel::data_beacons_t> beacons;
  std::vector<common::error_t> errors;
  // module::Subscription: LCM's member-function subscriptions trip UBSan.
  std::vector<std::shared_ptr<void>> subs;
  void subscribe(lcm::LCM& l) {
    subs.push_back(std::make_shared<module::Subscription<lowlevel::data_srfs_t>>(l, "LL_DATA_SRFS", [this](const lowlevel::data_srfs_t& m) { srfs.push_back(m); }));
    subs.push_back(std::make_shared<module::Subscription<lowlevel::data_odo_t>>(l, "LL_DATA_ODO", [this](const lowlevel::data_odo_t& m) { odo.push_back(m); }));
    subs.push_back(std::make_shared<module::Subscription<lowlevel::data_beacons_t>>(l, "LL_DATA_BEACONS", [this](const lowlevel::data_beacons_t& m) { beacons.push_back(m); }));
    subs.push_back(std::make_shared<module::Subscription<common::error_t>>(l, "CM_DATA_ERROR", [this](const common::error_t& m) { errors.push_back(m); }));
  }
  int errors_numbered(int n) const {
    int c = 0;
    for (const auto& e : errors) c += e.number == n;
    return c;
  }
};

void put_u16(std::vector<std::uint8_t>& v, unsigned x) {
  v.push_back(static_cast<std::uint8_t>(x & 0xff));
  v.push_back(static_cast<std::uint8_t>(x >> 8));
}

// Bus A: front SD1 0x10 and rear 0x11 (3 SRFs, 2 IRs each), SO1 0x20 whose
// counters advance by `tick_step` per reading (16-bit, wrapping).
struct BusA {
  std::mutex mu;
  std::int64_t left = 65500, right = 65500;  // wraps soon: the driver must not notice
  int tick_step = 100;
  bool rear_silent = false;
  bool so1_silent = false;  // GET_TICKS times out; the board still counts
  std::map<int, int> requests;  // address -> count

  rs485::Result respond(const rs485::Request& r) {
    std::lock_guard l(mu);
    ++requests[r.addr];
    if (r.addr == 0x10 || r.addr == 0x11) {
      if (r.addr == 0x11 && rear_silent) return FakeTransport::fail(rs485::Outcome::timeout);
      std::vector<std::uint8_t> d{3};
      const unsigned base = r.addr == 0x10 ? 100 : 300;
      put_u16(d, base);
      put_u16(d, 0xffff);  // no echo
      put_u16(d, base + 25);
      d.push_back(2);
      d.push_back(50);  // 0.1 m
      d.push_back(0);   // out of range
      return FakeTransport::ack(d);
    }
    if (r.addr == 0x20 && r.instr == rs485::so1::instr::kGetTicks) {
      if (so1_silent) return FakeTransport::fail(rs485::Outcome::timeout);
      left += tick_step;
      right += 2 * tick_step;
      std::vector<std::uint8_t> d;
      put_u16(d, static_cast<unsigned>(left & 0xffff));
      put_u16(d, static_cast<unsigned>(right & 0xffff));
      return FakeTransport::ack(d);
    }
    return FakeTransport::fail(rs485::Outcome::unknown_instruction);
  }
  void set_so1_silent(bool silent) {
    std::lock_guard l(mu);
    so1_silent = silent;
  }
  void roll(std::int64_t ticks) {  // the wheels turn while nobody reads
    std::lock_guard l(mu);
    left += ticks;
    right += 2 * ticks;
  }
  int count(int addr) {
    std::lock_guard l(mu);
    return requests[addr];
  }
};

Rs485Config bus_a_config(const std::string& so1_extra = "") {
  return parse_rs485_config(module::ConfigNode::parse(
      "module: {name: driver_rs485a, lcm_url: 'memq://', print_severity: none, send_severity: notice}\n"
      "driver_rs485:\n"
      "  bus: {device: a}\n"
      "  rate_hz: 40\n"
      "  sd1:\n"
      "    - {name: front, address: 0x10, srfs: [{index: 0, id: 4}, {index: 2, id: 6}], first_ir_id: 0}\n"
      "    - {name: rear, address: 0x11, first_srf_id: 8, first_ir_id: 2}\n"
      "  so1: {address: 0x20, wheel_radius_m: 0.1, ticks_per_rev: 1000, track_m: 0.5, wheelbase_m: 0.6" +
      so1_extra + "}\n"));
}

}  // namespace

TEST(Rs485Messages, RangesFollowTheSensorList) {
  Sd1Board b;
  b.srfs = {RangeSensor{2, 17, 0, 0, 0}, RangeSensor{0, 15, 0, 0, 0}, RangeSensor{5, 99, 0, 0, 0}};
  b.first_ir_id = 3;
  rs485::Sd1Distances d{{1.5, std::nullopt, 0.25}, {std::nullopt, 0.3}};
  lowlevel::data_srfs_t m{};
  append_ranges(b, d, m);
  // Index 5 was not reported by the board: left out.
  EXPECT_EQ(m.num_srfs, 2);
  EXPECT_EQ(m.srf_id, (std::vector<std::int16_t>{17, 15}));
  EXPECT_EQ(m.srf_range_m, (std::vector<float>{0.25f, 1.5f}));
  EXPECT_EQ(m.num_irs, 2);
  EXPECT_EQ(m.ir_id, (std::vector<std::int16_t>{3, 4}));
  EXPECT_EQ(m.ir_range_m, (std::vector<float>{-1.0f, 0.3f}));
}

TEST(Rs485Messages, BeaconsAndOdometry) {
  const auto m = beacons_message({{7, std::numbers::pi / 2, 200}, {3, 0.0, 10}});
  EXPECT_EQ(m.count, 2);
  EXPECT_EQ(m.id, (std::vector<std::int16_t>{7, 3}));
  EXPECT_FLOAT_EQ(m.bearing_rad[0], static_cast<float>(std::numbers::pi / 2));
  ChassisGeometry g;
  g.wheel_radius_m = 0.1;
  g.ticks_per_rev = 1000;
  AckermannOdometry odo(g);
  const auto o = odo_message(odo, 250, 250, 0.25);
  EXPECT_EQ(o.ticks_left, 250);
  EXPECT_DOUBLE_EQ(o.interval_s, 0.25);
  EXPECT_NEAR(o.speed_mps, 2 * std::numbers::pi * 0.1, 1e-9);  // one revolution per second
  EXPECT_NEAR(o.yaw_rate_radps, 0, 1e-12);
}

TEST(Rs485Driver, PublishesRangesAndOdometry) {
  BusA a;
  FakeTransport t([&](const rs485::Request& r) { return a.respond(r); });
  auto cfg = bus_a_config();
  module::Module m(cfg.module, clock_);
  Rx rx;
  rx.subscribe(m.lcm());
  Rs485Driver d(m, cfg, t);
  m.request_state(module::State::Run, false, "test");
  spin(m, 300ms);

  ASSERT_GE(rx.srfs.size(), 3u);
  const auto& s = rx.srfs.back();
  EXPECT_EQ(s.module, "driver_rs485a");
  // front: the listed sensors only; rear: every reading, ids from 8.
  EXPECT_EQ(s.srf_id, (std::vector<std::int16_t>{4, 6, 8, 9, 10}));
  EXPECT_EQ(s.srf_range_m, (std::vector<float>{1.0f, 1.25f, 3.0f, -1.0f, 3.25f}));
  EXPECT_EQ(s.ir_id, (std::vector<std::int16_t>{0, 1, 2, 3}));
  EXPECT_EQ(s.ir_range_m, (std::vector<float>{0.1f, -1.0f, 0.1f, -1.0f}));
  EXPECT_GT(s.utime, 0);

  // The first reading is a baseline; every later one is an interval, also
  // across the 16-bit wrap.
  ASSERT_GE(rx.odo.size(), 2u);
  AckermannOdometry odo(cfg.so1->geometry);
  for (const auto& o : rx.odo) {
    EXPECT_EQ(o.ticks_left, 100);
    EXPECT_EQ(o.ticks_right, 200);
    EXPECT_GT(o.interval_s, 0.0);
    const auto want = odo.from_ticks(100, 200, o.interval_s);
    EXPECT_DOUBLE_EQ(o.speed_mps, want.speed_mps);
    EXPECT_DOUBLE_EQ(o.yaw_rate_radps, want.yaw_rate_radps);
    EXPECT_GT(o.yaw_rate_radps, 0);  // right wheel faster: a left turn
  }
  for (int n : {kErrTransaction, kErrPassive, kErrOff, kErrRecovered}) EXPECT_EQ(rx.errors_numbered(n), 0);
}

TEST(Rs485Driver, PauseStopsPollingAndRunResumes) {
  BusA a;
  FakeTransport t([&](const rs485::Request& r) { return a.respond(r); });
  auto cfg = bus_a_config();
  module::Module m(cfg.module, clock_);
  Rx rx;
  rx.subscribe(m.lcm());
  Rs485Driver d(m, cfg, t);
  m.request_state(module::State::Run, false, "test");
  spin(m, 100ms);
  m.request_state(module::State::Pause, false, "test");
  spin(m, 20ms);
  const int polled = a.count(0x10);
  const auto odo_before = rx.odo.size();
  spin(m, 200ms);
  EXPECT_EQ(a.count(0x10), polled);
  EXPECT_EQ(rx.odo.size(), odo_before);
  m.request_state(module::State::Run, false, "test");
  spin(m, 200ms);
  EXPECT_GT(a.count(0x10), polled + 3);
  // After the pause a new baseline: no interval spans the pause.
  ASSERT_GT(rx.odo.size(), odo_before);
  for (std::size_t i = odo_before; i < rx.odo.size(); ++i) EXPECT_LT(rx.odo[i].interval_s, 0.15);
}

// The BR-SO1 does not answer for `gap`, while the wheels roll `rolled` ticks
// (left; right twice as many); returns the odometry published after it.
std::vector<lowlevel::data_odo_t> odometry_after_gap(Rs485Config cfg, std::chrono::milliseconds gap,
                                                     std::int64_t rolled, Rx& rx) {
  BusA a;
  FakeTransport t([&](const rs485::Request& r) { return a.respond(r); });
  module::Module m(cfg.module, clock_);
  rx.subscribe(m.lcm());
  Rs485Driver d(m, cfg, t);
  m.request_state(module::State::Run, false, "test");
  spin(m, 100ms);
  a.set_so1_silent(true);
  spin(m, 30ms);  // a poll in flight may still have answered
  const auto before = rx.odo.size();
  spin(m, gap);
  a.roll(rolled);
  a.set_so1_silent(false);
  spin(m, 100ms);
  rx.subs.clear();  // they hold on to the module's LCM
  return {rx.odo.begin() + static_cast<std::ptrdiff_t>(before), rx.odo.end()};
}

TEST(Rs485Driver, OdometryKeepsTheTicksOfAGapWithoutAmbiguity) {
  // 2.5 s without an answer: 5000 ticks (3.1 m, 1.3 m/s on the left wheel)
  // is far from the 32768 of an ambiguous 16-bit wrap at 1.5 m/s (13.7 s).
  Rx rx;
  const auto after = odometry_after_gap(bus_a_config(), 2500ms, 5000, rx);
  ASSERT_GE(after.size(), 2u);
  const auto& o = after.front();
  EXPECT_EQ(o.ticks_left, 5000 + 100);  // the gap plus the poll that ended it
  EXPECT_EQ(o.ticks_right, 10000 + 200);
  // The interval spans the whole gap, so the speed is the mean over it.
  EXPECT_GT(o.interval_s, 2.5);
  EXPECT_LT(o.interval_s, 3.0);
  const auto want = AckermannOdometry(bus_a_config().so1->geometry).from_ticks(5100, 10200, o.interval_s);
  EXPECT_DOUBLE_EQ(o.speed_mps, want.speed_mps);
  for (std::size_t i = 1; i < after.size(); ++i) EXPECT_EQ(after[i].ticks_left, 100);
  EXPECT_EQ(rx.errors_numbered(kErrOdoGap), 0);
}

TEST(Rs485Driver, OdometryDropsAGapThatCouldHideAWrap) {
  // At 40 m/s the 16-bit counters could wrap by half in 0.51 s: a 0.8 s gap
  // is ambiguous, so it starts a new baseline and says so.
  Rx rx;
  const auto after = odometry_after_gap(bus_a_config(", max_speed_mps: 40"), 800ms, 5000, rx);
  ASSERT_GE(after.size(), 1u);
  for (const auto& o : after) {
    EXPECT_EQ(o.ticks_left, 100);
    EXPECT_LT(o.interval_s, 0.2);
  }
  EXPECT_EQ(rx.errors_numbered(kErrOdoGap), 1);
}

TEST(Rs485Driver, SilentBoardIsReportedOnceAndTheOtherStillPublished) {
  BusA a;
  a.rear_silent = true;
  FakeTransport t([&](const rs485::Request& r) { return a.respond(r); });
  auto cfg = bus_a_config();
  module::Module m(cfg.module, clock_);
  Rx rx;
  rx.subscribe(m.lcm());
  Rs485Driver d(m, cfg, t);
  m.request_state(module::State::Run, false, "test");
  spin(m, 250ms);
  ASSERT_FALSE(rx.srfs.empty());
  EXPECT_EQ(rx.srfs.back().srf_id, (std::vector<std::int16_t>{4, 6}));
  EXPECT_EQ(rx.errors_numbered(kErrTransaction), 1);
  for (const auto& e : rx.errors) {
    if (e.number != kErrTransaction) continue;
    EXPECT_NE(e.text.find("rear (0x11): GET_BOTH failed"), std::string::npos) << e.text;
    EXPECT_EQ(e.type, static_cast<std::int8_t>(module::ErrorType::Timeout));
    EXPECT_EQ(e.severity, static_cast<std::int8_t>(module::Severity::Warning));
  }
  {
    std::lock_guard l(a.mu);
    a.rear_silent = false;
  }
  spin(m, 100ms);
  EXPECT_EQ(rx.errors_numbered(kErrRecovered), 1);
  EXPECT_EQ(rx.srfs.back().num_srfs, 5);
}

TEST(Rs485Driver, OffNodeIsNotPolledUntilReset) {
  BusA a;
  FakeTransport t([&](const rs485::Request& r) { return a.respond(r); });
  auto cfg = bus_a_config();
  module::Module m(cfg.module, clock_);
  Rx rx;
  rx.subscribe(m.lcm());
  std::atomic<int> rear_state{static_cast<int>(rs485::NodeState::passive)};
  NodeStatusFn status = [&](std::uint8_t addr) -> std::optional<rs485::NodeStatus> {
    if (addr != 0x11) return rs485::NodeStatus{addr, rs485::NodeState::active, 0};
    return rs485::NodeStatus{addr, static_cast<rs485::NodeState>(rear_state.load()), 200};
  };
  Rs485Driver d(m, cfg, t, status);
  m.request_state(module::State::Run, false, "test");
  spin(m, 100ms);
  EXPECT_EQ(rx.errors_numbered(kErrPassive), 1);  // once, not per poll
  EXPECT_GT(a.count(0x11), 0);                    // passive: still polled

  rear_state = static_cast<int>(rs485::NodeState::off);
  spin(m, 60ms);
  const int polled = a.count(0x11);
  spin(m, 200ms);
  EXPECT_EQ(a.count(0x11), polled);
  EXPECT_EQ(rx.errors_numbered(kErrOff), 1);
  ASSERT_FALSE(rx.srfs.empty());
  EXPECT_EQ(rx.srfs.back().num_srfs, 2);  // the front board alone
  bool named = false;
  for (const auto& e : rx.errors) named |= e.text.find("reset-node 0x11") != std::string::npos;
  EXPECT_TRUE(named);

  rear_state = static_cast<int>(rs485::NodeState::active);  // advee-rs485ctl reset-node 0x11
  spin(m, 100ms);
  EXPECT_GT(a.count(0x11), polled);
  EXPECT_EQ(rx.errors_numbered(kErrRecovered), 1);
  EXPECT_EQ(rx.srfs.back().num_srfs, 5);
}

TEST(Rs485Driver, ActiveBeaconsReachTheScanner) {
  std::mutex mu;
  std::vector<std::vector<std::uint8_t>> set_ids;
  FakeTransport t([&](const rs485::Request& r) {
    std::lock_guard l(mu);
    if (r.instr == rs485::sbs1::instr::kSetBeaconIds) {
      set_ids.push_back(r.data);
      return FakeTransport::ack();
    }
    // Two beacons: id 2 at 90.00 degrees, id 5 at 359.99.
    std::vector<std::uint8_t> d{2, 2};
    put_u16(d, 9000);
    d.push_back(100);
    d.push_back(5);
    put_u16(d, 35999);
    d.push_back(50);
    return FakeTransport::ack(d);
  });
  auto cfg = parse_rs485_config(module::ConfigNode::parse(
      "module: {name: driver_rs485b, lcm_url: 'memq://', print_severity: none}\n"
      "driver_rs485:\n  bus: {device: b}\n  rate_hz: 20\n  sbs1: {address: 0x30, beacon_ids: [1]}\n"));
  module::Module m(cfg.module, clock_);
  Rx rx;
  rx.subscribe(m.lcm());
  Rs485Driver d(m, cfg, t);
  m.request_state(module::State::Run, false, "test");
  spin(m, 120ms);
  {
    std::lock_guard l(mu);
    ASSERT_EQ(set_ids.size(), 1u);  // the configured ids once, not on every poll
    EXPECT_EQ(set_ids[0], (std::vector<std::uint8_t>{1}));
  }
  ASSERT_FALSE(rx.beacons.empty());
  const auto& b = rx.beacons.back();
  EXPECT_EQ(b.module, "driver_rs485b");
  EXPECT_EQ(b.id, (std::vector<std::int16_t>{2, 5}));
  EXPECT_FLOAT_EQ(b.bearing_rad[0], static_cast<float>(std::numbers::pi / 2));
  EXPECT_NEAR(b.bearing_rad[1], 2 * std::numbers::pi * 35999 / 36000, 1e-5);

  lowlevel::data_active_beacons_t ab{};
  ab.module = "planner";
  ab.id = {4, 9, 12};
  ab.count = 3;
  m.lcm().publish("LL_DATA_ACTIVE_BEACONS", &ab);
  spin(m, 120ms);
  std::lock_guard l(mu);
  ASSERT_EQ(set_ids.size(), 2u);
  EXPECT_EQ(set_ids[1], (std::vector<std::uint8_t>{4, 9, 12}));
}
