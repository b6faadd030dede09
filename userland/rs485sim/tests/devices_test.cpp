// SPDX-License-Identifier: GPL-2.0
// Each board's data layout (shared/specs/rs485-protocol.md) from its readings.
#include <gtest/gtest.h>

#include "advee/rs485sim/bus_sim.hpp"
#include "advee/rs485sim/devices.hpp"
#include "test_util.hpp"

namespace advee::rs485sim {
namespace {

using test::bytes;
using test::kT0;
using namespace std::chrono_literals;

template <typename D>
struct OnBus {
  BusSim bus{"t", true};
  D* dev = static_cast<D*>(&bus.add(std::make_unique<D>(0x42)));
  std::vector<std::uint8_t> ask(std::uint8_t instr, std::vector<std::uint8_t> data = {},
                                std::uint8_t want_flags = kRespAck, Clock::time_point now = kT0) {
    const auto r = test::transact(bus, Frame{0x42, instr, 0, std::move(data)}, 0, now);
    EXPECT_EQ(r.size(), 1u);
    if (r.empty()) return {};
    EXPECT_EQ(r[0].frame.flags, want_flags);
    return r[0].frame.data;
  }
};

TEST(Sd1, GetBothLayoutWithNoEchoAndOutOfRange) {
  OnBus<Sd1> t;
  for (std::size_t i = 0; i < Sd1::kSrf; ++i) t.dev->set_srf(i, 0.01 * double(i + 1));
  t.dev->set_srf(3, 2.5);
  t.dev->set_srf(7, std::nullopt);
  t.dev->set_ir(0, 0.1);   // 100 mm = 50 units of 2 mm
  t.dev->set_ir(1, 0.6);   // beyond 510 mm: out of range
  EXPECT_EQ(t.ask(Sd1::kGetBoth),
            bytes({8, 1, 0, 2, 0, 3, 0, 250, 0, 5, 0, 6, 0, 7, 0, 0xff, 0xff, 2, 50, 0}));
  EXPECT_EQ(t.ask(Sd1::kGetSrf).size(), 17u);
  EXPECT_EQ(t.ask(Sd1::kGetIr), bytes({2, 50, 0}));
}

TEST(Sd1, ZeroReadingsAndFarSrfSaturateBelowNoEcho) {
  OnBus<Sd1> t;
  t.dev->set_srf(0, 1000.0);  // 100000 cm does not fit: the largest real reading
  t.dev->set_ir(0, 0.0);
  const auto d = t.ask(Sd1::kGetBoth);
  EXPECT_EQ(d[1], 0xfe);
  EXPECT_EQ(d[2], 0xff);
  EXPECT_EQ(d[3], 0);  // SRF 1 never set: 0 cm
  EXPECT_EQ(d[19], 0);  // IR 0 m: out of range
}

TEST(Sd1, PauseSourcesLatchUntilCleared) {
  OnBus<Sd1> t;
  t.dev->raise_pause(0x01);
  t.dev->raise_pause(0x08);
  EXPECT_EQ(t.ask(Sd1::kGetPauseSrc), bytes({0x09}));
  EXPECT_EQ(t.ask(Sd1::kGetPauseSrc), bytes({0x09}));
  EXPECT_TRUE(t.ask(Sd1::kClearPauseSrc).empty());
  EXPECT_EQ(t.ask(Sd1::kGetPauseSrc), bytes({0x00}));
}

TEST(So1, CountersWrapInEachWidth) {
  OnBus<So1> t;
  t.dev->set_ticks(130, -2, kT0);
  EXPECT_EQ(t.ask(So1::kGetTicks, bytes({1})), bytes({0x82, 0xfe}));  // 130 wraps to -126
  EXPECT_EQ(t.ask(So1::kGetTicks, bytes({2})), bytes({0x82, 0x00, 0xfe, 0xff}));
  t.dev->set_ticks(40000, -40000, kT0);
  EXPECT_EQ(t.ask(So1::kGetTicks, bytes({2})), bytes({0x40, 0x9c, 0xc0, 0x63}));
  t.dev->set_ticks(0x1'0000'0005LL, -1, kT0);
  EXPECT_EQ(t.ask(So1::kGetTicks, bytes({4})), bytes({5, 0, 0, 0, 0xff, 0xff, 0xff, 0xff}));
  EXPECT_EQ(t.ask(So1::kGetTicks).size(), 4u);  // default width 2
}

TEST(So1, BadWidthIsADeviceError) {
  OnBus<So1> t;
  EXPECT_EQ(t.ask(So1::kGetTicks, bytes({3}), kRespDevErr), bytes({3}));
}

TEST(So1, TicksGrowWithTheRateAndResetToZero) {
  OnBus<So1> t;
  t.dev->set_ticks(0, 0, kT0);
  t.dev->set_rate(100.0, -50.0, kT0);
  EXPECT_EQ(t.dev->ticks(kT0 + 2s), (std::array<std::int64_t, 2>{200, -100}));
  EXPECT_TRUE(t.ask(So1::kResetTicks, {}, kRespAck, kT0 + 2s).empty());
  EXPECT_EQ(t.dev->ticks(kT0 + 3s), (std::array<std::int64_t, 2>{100, -50}));
}

TEST(Sbs1, ReportsVisibleBeaconsAmongTheIdsSet) {
  OnBus<Sbs1> t;
  t.dev->set_beacon(1, Sbs1::Sighting{90.0, 200});
  t.dev->set_beacon(2, Sbs1::Sighting{-0.5, 10});     // wraps to 359.50
  t.dev->set_beacon(3, Sbs1::Sighting{360.0, 99});    // 360 is 0
  t.dev->set_beacon(9, Sbs1::Sighting{10.0, 1});      // visible but not asked for
  EXPECT_TRUE(t.ask(Sbs1::kSetBeaconIds, bytes({1, 2, 3, 4})).empty());
  EXPECT_EQ(t.ask(Sbs1::kGetBeaconData),
            bytes({3, 1, 0x28, 0x23, 200, 2, 0x6e, 0x8c, 10, 3, 0, 0, 99}));
  EXPECT_TRUE(t.ask(Sbs1::kSetBeaconIds, {}).empty());
  EXPECT_EQ(t.ask(Sbs1::kGetBeaconData), bytes({0}));
  EXPECT_FALSE(t.ask(Sbs1::kGetDebugData).empty());
}

TEST(Psc1, SetStatusChangesOnlyMaskedChannels) {
  OnBus<Psc1> t;
  t.dev->set_boot_status(0xf0);
  EXPECT_EQ(t.ask(Psc1::kSetPwrStatus, bytes({0x0f, 0x05})), bytes({0xf5}));
  EXPECT_EQ(t.ask(Psc1::kSetPwrStatus, bytes({0x80, 0x00})), bytes({0x75}));
  EXPECT_EQ(t.ask(Psc1::kGetPwrStatus), bytes({0x75}));
  EXPECT_TRUE(t.ask(Psc1::kSetPwrStatus, bytes({0x01}), kRespDevErr).empty());
}

TEST(Psc1, CurrentsInMilliampsZeroWhenOffNoSensorStaysMarked) {
  OnBus<Psc1> t;
  t.dev->set_boot_status(0x03);
  t.dev->set_current(0, 1.25);
  t.dev->set_current(1, std::nullopt);
  t.dev->set_current(2, 0.5);  // channel 2 is off
  EXPECT_EQ(t.ask(Psc1::kGetCurrents),
            bytes({0xe2, 0x04, 0xff, 0xff, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0}));
}

TEST(Psc1, ResetBootsAndSendsAPowerEvent) {
  OnBus<Psc1> t;
  t.dev->set_boot_status(0x81);
  t.dev->set_status(0x00);
  const auto r = test::transact(t.bus, Frame{0x42, kInstrReset, 0, {}});
  ASSERT_EQ(r.size(), 2u);
  // The event is queued at once, the ACK after the response time.
  EXPECT_EQ(r[0].frame, (Frame{0x42, Psc1::kPowerEvent, kRespEvent, bytes({0x81})}));
  EXPECT_EQ(r[1].frame, (Frame{0x42, kInstrReset, kRespAck, {}}));
}

TEST(Psc1, PeriodicEvents) {
  OnBus<Psc1> t;
  t.dev->set_pause_state(true, 0x02);
  t.dev->set_pause_period(100ms, kT0);
  EXPECT_EQ(t.bus.next_deadline(), kT0 + 100ms);
  t.bus.poll(kT0 + 50ms);
  EXPECT_TRUE(t.bus.take_due(kT0 + 1s).empty());
  t.bus.poll(kT0 + 100ms);
  t.bus.poll(kT0 + 200ms);
  const auto tx = t.bus.take_due(kT0 + 1s);
  ASSERT_EQ(tx.size(), 2u);
  EXPECT_EQ(test::decode(tx[1].words)->frame, (Frame{0x42, Psc1::kPauseEvent, kRespEvent, bytes({1, 2})}));
}

}  // namespace
}  // namespace advee::rs485sim
