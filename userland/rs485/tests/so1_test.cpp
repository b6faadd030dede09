// SPDX-License-Identifier: GPL-2.0
#include "advee/rs485/devices/so1.hpp"

#include <gtest/gtest.h>

#include <limits>

#include "advee/rs485/fake_transport.hpp"

namespace advee::rs485 {
namespace {

using Bytes = std::vector<std::uint8_t>;

TEST(Rs485So1, DecodesSignedCountersOfEachWidth) {
  EXPECT_EQ(*So1::decode_ticks(Bytes{0x7F, 0x80}, 1), (So1RawTicks{1, 127, -128}));
  EXPECT_EQ(*So1::decode_ticks(Bytes{0x34, 0x12, 0xFF, 0xFF}, 2), (So1RawTicks{2, 0x1234, -1}));
  EXPECT_EQ(*So1::decode_ticks(Bytes{0, 0, 0, 0x80, 0xFF, 0xFF, 0xFF, 0x7F}, 4),
            (So1RawTicks{4, std::numeric_limits<std::int32_t>::min(), std::numeric_limits<std::int32_t>::max()}));
  EXPECT_EQ(*So1::decode_ticks(Bytes{0, 0}, 1), (So1RawTicks{1, 0, 0}));
}

TEST(Rs485So1, WrongLengthOrWidthIsAnError) {
  EXPECT_EQ(So1::decode_ticks(Bytes{1, 2, 3}, 2).error(), Outcome::bad_response);
  EXPECT_EQ(So1::decode_ticks(Bytes{1, 2, 3, 4, 5}, 2).error(), Outcome::bad_response);
  EXPECT_EQ(So1::decode_ticks(Bytes{}, 1).error(), Outcome::bad_response);
  EXPECT_EQ(So1::decode_ticks(Bytes{1, 2, 3, 4, 5, 6}, 3).error(), std::errc::invalid_argument);
  FakeTransport t;
  EXPECT_EQ(So1(t, 1).raw_ticks(8).error(), std::errc::invalid_argument);
  EXPECT_TRUE(t.requests().empty());  // nothing sent for a bad argument
}

// Feeds a sequence of true positions through a counter of `width` bytes (as
// the board would send them) and checks the accumulated count every step.
void expect_tracks(unsigned width, std::int64_t start, std::int64_t step, int steps) {
  const unsigned bits = 8 * width;
  auto wrap = [&](std::int64_t v) {
    const std::uint64_t m = (std::uint64_t{1} << bits) - 1;
    std::uint64_t u = static_cast<std::uint64_t>(v) & m;
    if (u >> (bits - 1)) u |= ~m;  // sign-extend
    return static_cast<std::int64_t>(u);
  };
  TickAccumulator acc;
  std::int64_t pos = start;
  for (int i = 0; i < steps; ++i, pos += step) {
    const auto c = acc.update({width, wrap(pos), wrap(-pos)});
    ASSERT_EQ(c.left, pos) << "width " << width << " step " << i;
    ASSERT_EQ(c.right, -pos) << "width " << width << " step " << i;
  }
}

TEST(Rs485So1, WrapAroundForwardInEachWidth) {
  expect_tracks(1, 0, 100, 50);           // wraps 127 -> -128 many times
  expect_tracks(2, 0, 30000, 20);         // 32767 -> -32768
  expect_tracks(4, 0, 2000000000, 10);    // 2^31 - 1 -> -2^31
}

TEST(Rs485So1, WrapAroundBackwardInEachWidth) {
  expect_tracks(1, 0, -127, 50);
  expect_tracks(2, 0, -32767, 20);
  expect_tracks(4, 0, -2147483647, 10);
}

TEST(Rs485So1, WrapExactlyAtTheBoundary) {
  TickAccumulator acc;
  acc.update({2, 32767, -32768});
  const auto c = acc.update({2, -32768, 32767});  // +1 and -1 across the wrap
  EXPECT_EQ(c.left, 32768);
  EXPECT_EQ(c.right, -32769);
}

TEST(Rs485So1, FirstReadingIsTheCountSinceTheBoardReset) {
  TickAccumulator acc;
  EXPECT_EQ(acc.update({2, -5, 7}), (So1Counts{-5, 7}));
  acc.reset();
  EXPECT_EQ(acc.counts(), (So1Counts{0, 0}));
  EXPECT_EQ(acc.update({1, 3, 0}), (So1Counts{3, 0}));
}

TEST(Rs485So1, CountsAndResetOverTheTransport) {
  std::int16_t left = 32000;
  FakeTransport t([&](const Request& r) {
    if (r.instr == so1::instr::kResetTicks) {
      left = 0;
      return FakeTransport::ack();
    }
    EXPECT_EQ(r.instr, so1::instr::kGetTicks);
    EXPECT_EQ(r.data, Bytes{2});
    const auto u = static_cast<std::uint16_t>(left);
    return FakeTransport::ack({static_cast<std::uint8_t>(u), static_cast<std::uint8_t>(u >> 8), 0, 0});
  });
  So1 odo(t, 0x11);
  EXPECT_EQ(odo.counts()->left, 32000);
  left = static_cast<std::int16_t>(32000 + 1000 - 65536);  // the board wrapped
  EXPECT_EQ(odo.counts()->left, 33000);
  EXPECT_FALSE(odo.reset_ticks());
  EXPECT_EQ(odo.accumulator().counts().left, 0);
  EXPECT_EQ(odo.counts()->left, 0);
}

TEST(Rs485So1, FailedResetKeepsTheAccumulator) {
  FakeTransport t([](const Request& r) {
    if (r.instr == so1::instr::kGetTicks) return FakeTransport::ack({10, 0, 20, 0});
    return FakeTransport::fail(Outcome::timeout);
  });
  So1 odo(t, 0x11);
  ASSERT_TRUE(odo.counts());
  EXPECT_EQ(odo.reset_ticks(), Outcome::timeout);
  EXPECT_EQ(odo.accumulator().counts(), (So1Counts{10, 20}));
}

}  // namespace
}  // namespace advee::rs485
