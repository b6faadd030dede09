// SPDX-License-Identifier: GPL-2.0
#include <gtest/gtest.h>

#include "advee/rs485sim/wire_frame.hpp"
#include "test_util.hpp"

namespace advee::rs485sim {
namespace {

using test::bytes;

struct Collect {
  std::vector<Frame> frames;
  Receiver rx{[this](const Frame& f) { frames.push_back(f); }};
};

TEST(EncodeWords, NinthBitOnTheAddressOnlyAndCrcOfTheSpec) {
  // The CRC checked against a bitwise CRC-8/MAXIM (poly 0x8C reflected), not the table.
  const auto w = encode_words(Frame{0x10, 0xfe, 0x00, {}});
  ASSERT_EQ(w.size(), 5u);
  EXPECT_EQ(w[0], 0x110);
  EXPECT_EQ(w[1], 0xfe);
  EXPECT_EQ(w[2], 0x00);
  EXPECT_EQ(w[3], 0x00);
  std::uint8_t crc = 0;
  for (std::uint8_t b : {0x10, 0xfe, 0x00, 0x00}) {
    crc ^= b;
    for (int i = 0; i < 8; ++i) crc = (crc & 1) ? static_cast<std::uint8_t>((crc >> 1) ^ 0x8c) : crc >> 1;
  }
  EXPECT_EQ(w[4], crc);
  for (std::size_t i = 1; i < w.size(); ++i) EXPECT_FALSE(w[i] & kWordBit9) << i;
}

TEST(Receiver, ParsesAFrameWithData) {
  Collect c;
  const Frame f{0x20, 0x01, 0x00, bytes({4})};
  c.rx.feed(encode_words(f));
  ASSERT_EQ(c.frames.size(), 1u);
  EXPECT_EQ(c.frames[0], f);
  EXPECT_EQ(c.rx.stats().frames, 1u);
}

TEST(Receiver, DropsABadCrcAndCountsIt) {
  Collect c;
  c.rx.feed(encode_words(Frame{0x20, 0x01, 0x00, bytes({4})}, 0x01));
  EXPECT_TRUE(c.frames.empty());
  EXPECT_EQ(c.rx.stats().crc_errors, 1u);
}

TEST(Receiver, ResynchronisesOnTheNinthBitAfterGarbage) {
  Collect c;
  // Noise before any address, then a frame cut short by a new address character.
  std::vector<std::uint16_t> w{0x55, 0xaa, 0x01};
  const auto cut = encode_words(Frame{0x10, 0x10, 0x00, bytes({1, 2, 3})});
  w.insert(w.end(), cut.begin(), cut.begin() + 5);
  const Frame good{0x11, 0x01, 0x00, {}};
  const auto g = encode_words(good);
  w.insert(w.end(), g.begin(), g.end());
  c.rx.feed(w);
  ASSERT_EQ(c.frames.size(), 1u);
  EXPECT_EQ(c.frames[0], good);
  EXPECT_EQ(c.rx.stats().noise, 3u);
  EXPECT_EQ(c.rx.stats().truncated, 1u);
}

TEST(Receiver, ABreakInsideAFrameDiscardsIt) {
  Collect c;
  auto w = encode_words(Frame{0x10, 0x01, 0x00, bytes({7, 8})});
  w.insert(w.begin() + 3, kWordBreak);
  c.rx.feed(w);
  EXPECT_TRUE(c.frames.empty());
  EXPECT_EQ(c.rx.stats().line_errors, 1u);
  c.rx.feed(encode_words(Frame{0x10, 0x01, 0x00, {}}));
  EXPECT_EQ(c.frames.size(), 1u);
}

TEST(Receiver, MaximumLengthFrame) {
  Collect c;
  Frame f{0x01, 0x02, 0x00, std::vector<std::uint8_t>(255, 0xa5)};
  c.rx.feed(encode_words(f));
  ASSERT_EQ(c.frames.size(), 1u);
  EXPECT_EQ(c.frames[0].data.size(), 255u);
}

}  // namespace
}  // namespace advee::rs485sim
