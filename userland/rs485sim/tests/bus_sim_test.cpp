// SPDX-License-Identifier: GPL-2.0
// The slave side of the protocol: dispatch, RESEND, NOACK, broadcast, faults.
#include <gtest/gtest.h>

#include "advee/rs485sim/bus_sim.hpp"
#include "advee/rs485sim/devices.hpp"
#include "test_util.hpp"

namespace advee::rs485sim {
namespace {

using test::bytes;
using test::kT0;
using test::transact;
using namespace std::chrono_literals;

class BusSimTest : public ::testing::Test {
 protected:
  BusSimTest() : bus("a", false, 7) {
    sd1 = static_cast<Sd1*>(&bus.add(std::make_unique<Sd1>(0x10)));
    so1 = static_cast<So1*>(&bus.add(std::make_unique<So1>(0x20)));
    sd1->set_response_time(500us, 500us);
    so1->set_response_time(200us, 2000us);
  }
  BusSim bus;
  Sd1* sd1;
  So1* so1;
};

TEST_F(BusSimTest, AnswersFirmwareVersionAfterTheResponseTime) {
  sd1->set_firmware(2, 5);
  bus.feed(encode_words(Frame{0x10, kInstrGetFwVersion, 0, {}}), kT0);
  EXPECT_TRUE(bus.take_due(kT0 + 499us).empty());
  const auto tx = bus.take_due(kT0 + 500us);
  ASSERT_EQ(tx.size(), 1u);
  const auto d = test::decode(tx[0].words);
  ASSERT_TRUE(d && d->crc_ok);
  EXPECT_EQ(d->frame, (Frame{0x10, kInstrGetFwVersion, kRespAck, bytes({2, 5})}));
}

TEST_F(BusSimTest, ResponseTimeStaysInTheConfiguredRange) {
  for (int i = 0; i < 200; ++i) {
    bus.feed(encode_words(Frame{0x20, So1::kGetTicks, 0, {}}), kT0);
    const auto d = bus.next_deadline();
    ASSERT_TRUE(d);
    EXPECT_GE(*d - kT0, 200us);
    EXPECT_LE(*d - kT0, 2000us);
    bus.take_due(kT0 + 1s);
  }
}

TEST_F(BusSimTest, OtherAddressesAndBadCrcGetNoAnswer) {
  EXPECT_TRUE(transact(bus, Frame{0x11, kInstrGetFwVersion, 0, {}}).empty());
  EXPECT_TRUE(transact(bus, Frame{0x10, kInstrGetFwVersion, 0, {}}, 0x33).empty());
  EXPECT_EQ(bus.receiver_stats().crc_errors, 1u);
  EXPECT_EQ(sd1->stats().requests, 0u);
}

TEST_F(BusSimTest, UnknownInstructionIsAnsweredUnkinstr) {
  const auto r = transact(bus, Frame{0x10, 0x77, 0, {}});
  ASSERT_EQ(r.size(), 1u);
  EXPECT_EQ(r[0].frame, (Frame{0x10, 0x77, kRespUnkInstr, {}}));
  EXPECT_EQ(sd1->stats().executed, 0u);
}

TEST_F(BusSimTest, ResendReturnsTheLastResponseWithoutExecutingAgain) {
  so1->set_ticks(100, 200, kT0);
  const auto first = transact(bus, Frame{0x20, So1::kGetTicks, 0, bytes({2})});
  ASSERT_EQ(first.size(), 1u);
  // The counters move; a RESEND must still return the old reading.
  so1->set_ticks(111, 222, kT0);
  const auto again = transact(bus, Frame{0x20, So1::kGetTicks, kReqResend, bytes({2})});
  ASSERT_EQ(again.size(), 1u);
  EXPECT_EQ(again[0].frame, first[0].frame);
  EXPECT_EQ(so1->stats().per_instr.at(So1::kGetTicks), 1u);
  EXPECT_EQ(so1->stats().resends, 1u);
}

TEST_F(BusSimTest, ResendAfterABadCrcOfANonIdempotentInstructionExecutesOnce) {
  so1->set_ticks(5, 5, kT0);
  so1->faults().bad_crc = FaultSpec{0.0, 1};
  const auto bad = transact(bus, Frame{0x20, So1::kResetTicks, 0, {}});
  ASSERT_EQ(bad.size(), 1u);
  EXPECT_FALSE(bad[0].crc_ok);
  so1->set_ticks(9, 9, kT0);  // the robot moved on after the reset
  const auto good = transact(bus, Frame{0x20, So1::kResetTicks, kReqResend, {}});
  ASSERT_EQ(good.size(), 1u);
  EXPECT_TRUE(good[0].crc_ok);
  EXPECT_EQ(good[0].frame.flags, kRespAck);
  EXPECT_EQ(so1->ticks(kT0), (std::array<std::int64_t, 2>{9, 9}));
  EXPECT_EQ(so1->stats().per_instr.at(So1::kResetTicks), 1u);
}

TEST_F(BusSimTest, ResendForAnotherInstructionIsNotAnswered) {
  transact(bus, Frame{0x10, kInstrGetFwVersion, 0, {}});
  EXPECT_TRUE(transact(bus, Frame{0x10, Sd1::kGetBoth, kReqResend, {}}).empty());
}

TEST_F(BusSimTest, NoAckExecutesWithoutAnswer) {
  sd1->raise_pause(0x3);
  EXPECT_TRUE(transact(bus, Frame{0x10, Sd1::kClearPauseSrc, kReqNoAck, {}}).empty());
  const auto r = transact(bus, Frame{0x10, Sd1::kGetPauseSrc, 0, {}});
  ASSERT_EQ(r.size(), 1u);
  EXPECT_EQ(r[0].frame.data, bytes({0}));
}

TEST_F(BusSimTest, BroadcastResetResetsEveryDeviceSilently) {
  so1->set_ticks(40, 41, kT0);
  sd1->raise_pause(0x1);
  EXPECT_TRUE(transact(bus, Frame{kBroadcast, kInstrReset, 0, {}}).empty());
  EXPECT_EQ(so1->ticks(kT0), (std::array<std::int64_t, 2>{0, 0}));
  const auto r = transact(bus, Frame{0x10, Sd1::kGetPauseSrc, 0, {}});
  ASSERT_EQ(r.size(), 1u);
  EXPECT_EQ(r[0].frame.data, bytes({0}));
  EXPECT_EQ(so1->stats().broadcasts, 1u);
  EXPECT_EQ(sd1->stats().broadcasts, 1u);
}

TEST_F(BusSimTest, NoAnswerFaultOnceThenNormal) {
  sd1->faults().no_answer = FaultSpec{0.0, 1};
  EXPECT_TRUE(transact(bus, Frame{0x10, Sd1::kGetBoth, 0, {}}).empty());
  EXPECT_EQ(transact(bus, Frame{0x10, Sd1::kGetBoth, 0, {}}).size(), 1u);
  EXPECT_EQ(sd1->stats().dropped, 1u);
  EXPECT_EQ(sd1->stats().per_instr.at(Sd1::kGetBoth), 1u);  // a request not heard is not executed
}

TEST_F(BusSimTest, UnkinstrFaultDoesNotExecute) {
  sd1->raise_pause(0x4);
  sd1->faults().unkinstr = FaultSpec{1.0, 0};
  const auto r = transact(bus, Frame{0x10, Sd1::kClearPauseSrc, 0, {}});
  ASSERT_EQ(r.size(), 1u);
  EXPECT_EQ(r[0].frame.flags, kRespUnkInstr);
  sd1->faults().unkinstr = {};
  EXPECT_EQ(transact(bus, Frame{0x10, Sd1::kGetPauseSrc, 0, {}})[0].frame.data, bytes({4}));
}

TEST_F(BusSimTest, SlowFaultDelaysTheAnswer) {
  sd1->faults().slow = FaultSpec{0.0, 1};
  sd1->faults().slow_delay = 150ms;
  bus.feed(encode_words(Frame{0x10, kInstrGetFwVersion, 0, {}}), kT0);
  EXPECT_TRUE(bus.take_due(kT0 + 150ms).empty());
  EXPECT_EQ(bus.take_due(kT0 + 150ms + 500us).size(), 1u);
}

TEST_F(BusSimTest, CorruptionProbabilityIsRoughlyHonoured) {
  sd1->faults().bad_crc = FaultSpec{0.1, 0};
  int bad = 0;
  for (int i = 0; i < 2000; ++i) {
    const auto r = transact(bus, Frame{0x10, Sd1::kGetSrf, 0, {}});
    ASSERT_EQ(r.size(), 1u);
    bad += !r[0].crc_ok;
  }
  // 10 % of 2000 = 200, sigma ~13: a wide band that a broken RNG use still misses.
  EXPECT_GT(bad, 140);
  EXPECT_LT(bad, 260);
}

TEST_F(BusSimTest, DuplicateAndBroadcastAddressesAreRefused) {
  EXPECT_THROW(bus.add(std::make_unique<Sbs1>(0x10)), UsageError);
  EXPECT_THROW(bus.add(std::make_unique<Sbs1>(0xff)), UsageError);
}

TEST(BusSimEvents, EventsGoOutOnlyOnAFullDuplexBus) {
  BusSim full("power", true), half("a", false);
  auto& p = static_cast<Psc1&>(full.add(std::make_unique<Psc1>(0x01)));
  auto& q = static_cast<Psc1&>(half.add(std::make_unique<Psc1>(0x01)));
  p.send_pause_event(true, 0x05);
  q.send_pause_event(true, 0x05);
  const auto tx = full.take_due(Clock::now() + 1s);
  ASSERT_EQ(tx.size(), 1u);
  const auto d = test::decode(tx[0].words);
  ASSERT_TRUE(d && d->crc_ok);
  EXPECT_EQ(d->frame, (Frame{0x01, Psc1::kPauseEvent, kRespEvent, bytes({1, 5})}));
  EXPECT_TRUE(half.take_due(Clock::now() + 1s).empty());
}

}  // namespace
}  // namespace advee::rs485sim
