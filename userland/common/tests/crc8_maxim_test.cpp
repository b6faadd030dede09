// SPDX-License-Identifier: GPL-2.0
#include "advee/crc8_maxim.hpp"

#include <gtest/gtest.h>

#include <string_view>
#include <vector>

namespace {

std::vector<std::uint8_t> bytes(std::string_view s) { return {s.begin(), s.end()}; }

TEST(Crc8Maxim, CheckValueOfTheCatalogue) {
  // CRC-8/MAXIM catalogue check value for "123456789".
  EXPECT_EQ(advee::crc8_maxim(bytes("123456789")), 0xA1);
}

TEST(Crc8Maxim, EmptyInputKeepsTheSeed) {
  EXPECT_EQ(advee::crc8_maxim({}), 0x00);
  EXPECT_EQ(advee::crc8_maxim({}, 0x5A), 0x5A);
}

TEST(Crc8Maxim, IncrementalEqualsOneShot) {
  const auto all = bytes("\x05\xFE\x00\x02\x01\x07");
  const std::span<const std::uint8_t> s(all);
  for (std::size_t cut = 0; cut <= all.size(); ++cut)
    EXPECT_EQ(advee::crc8_maxim(s.subspan(cut), advee::crc8_maxim(s.first(cut))), advee::crc8_maxim(s))
        << "cut at " << cut;
}

TEST(Crc8Maxim, AppendingTheCrcGivesZero) {
  // Receivers check a frame by running the CRC over data + CRC byte.
  auto frame = bytes("\x12\x01\x00\x03\xAA\xBB\xCC");
  frame.push_back(advee::crc8_maxim(frame));
  EXPECT_EQ(advee::crc8_maxim(frame), 0x00);
}

TEST(Crc8Maxim, DetectsEverySingleBitError) {
  auto frame = bytes("\x20\x02\x01\x04\x10\x20\x30\x40");
  const std::uint8_t good = advee::crc8_maxim(frame);
  for (std::size_t i = 0; i < frame.size(); ++i) {
    for (int bit = 0; bit < 8; ++bit) {
      frame[i] ^= static_cast<std::uint8_t>(1u << bit);
      EXPECT_NE(advee::crc8_maxim(frame), good) << "byte " << i << " bit " << bit;
      frame[i] ^= static_cast<std::uint8_t>(1u << bit);
    }
  }
}

}  // namespace
