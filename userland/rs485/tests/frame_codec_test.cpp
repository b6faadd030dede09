// SPDX-License-Identifier: GPL-2.0
// Frame vectors computed by hand from shared/specs/rs485-protocol.md
// (CRC-8/MAXIM: reflected polynomial 0x8C, init 0, no final XOR).
#include "advee/rs485/frame_codec.hpp"

#include <gtest/gtest.h>

#include <string_view>

#include "advee/crc8_maxim.hpp"

namespace advee::rs485 {
namespace {

using Bytes = std::vector<std::uint8_t>;

TEST(Rs485Crc, CheckValueOfTheSpec) {
  constexpr std::string_view check = "123456789";
  const Bytes b(check.begin(), check.end());
  EXPECT_EQ(crc8_maxim(b), 0xA1);
}

// Expected CRCs computed bit by bit (shift right, XOR 0x8C when the bit
// shifted out is 1), independently of the table in crc8_maxim.cpp.
TEST(Rs485Frame, WireVectorsOfTheSpec) {
  // GET_FW_VERSION request to node 0x10.
  EXPECT_EQ(encode_wire_frame({0x10, 0xFE, 0x00, {}}), (Bytes{0x10, 0xFE, 0x00, 0x00, 0x41}));
  // Its response: ACK, firmware 1.3.
  EXPECT_EQ(encode_wire_frame({0x10, 0xFE, 0x01, {0x01, 0x03}}), (Bytes{0x10, 0xFE, 0x01, 0x02, 0x01, 0x03, 0xB9}));
  // Broadcast RESET.
  EXPECT_EQ(encode_wire_frame({kBroadcast, standard_instr::kReset, 0x00, {}}), (Bytes{0xFF, 0xFF, 0x00, 0x00, 0x39}));
  // A little-endian u16 0x1234 in a response to node 5.
  EXPECT_EQ(encode_wire_frame({0x05, 0x01, 0x01, {0x34, 0x12}}), (Bytes{0x05, 0x01, 0x01, 0x02, 0x34, 0x12, 0xD1}));
}

TEST(Rs485Frame, CrcOfTheHandComputedVectors) {
  // One byte: crc8(0x01) = 0x5E (the table entry of 1 for 0x8C).
  EXPECT_EQ(crc8_maxim(Bytes{0x01}), 0x5E);
  // 0x02 -> 0xBC, 0x80 -> 0x8C (a single 1 bit shifted out of the top).
  EXPECT_EQ(crc8_maxim(Bytes{0x02}), 0xBC);
  EXPECT_EQ(crc8_maxim(Bytes{0x80}), 0x8C);
  // A frame whose CRC makes the total CRC zero: the property a receiver
  // can check (CRC over frame + its CRC = 0 for this reflected CRC).
  const Bytes frame = encode_wire_frame({0x05, 0x01, 0x01, {0x34, 0x12}});
  EXPECT_EQ(crc8_maxim(frame), 0x00);
}

TEST(Rs485Frame, LdiscEncodingIsHeaderAndData) {
  EXPECT_EQ(encode_ldisc_frame({0x22, 0x01, 0x02, {0xAA, 0xBB}}), (Bytes{0x22, 0x01, 0x02, 0x02, 0xAA, 0xBB}));
  EXPECT_THROW(encode_ldisc_frame({0, 0, 0, Bytes(256)}), std::length_error);
  EXPECT_EQ(encode_ldisc_frame({0, 0, 0, Bytes(255)}).size(), 259u);
}

TEST(Rs485Frame, LdiscDecodingChecksTheLength) {
  auto f = decode_ldisc_frame(Bytes{0x40, 0x40, 0x08, 0x02, 0x01, 0x05});
  ASSERT_TRUE(f);
  EXPECT_EQ(*f, (Frame{0x40, 0x40, 0x08, {0x01, 0x05}}));
  EXPECT_TRUE(f->is_event());
  EXPECT_EQ(decode_ldisc_frame(Bytes{0x40, 0x40, 0x08}).error(), Outcome::bad_response);
  EXPECT_EQ(decode_ldisc_frame(Bytes{0x40, 0x40, 0x08, 0x02, 0x01}).error(), Outcome::bad_response);
  EXPECT_EQ(decode_ldisc_frame(Bytes{0x40, 0x40, 0x08, 0x00, 0x01}).error(), Outcome::bad_response);
}

WireParser::Result feed_all(WireParser& p, const Bytes& wire) {
  WireParser::Result r = WireParser::Result::incomplete;
  for (std::size_t i = 0; i < wire.size(); ++i) r = p.feed(wire[i], i == 0);
  return r;
}

TEST(Rs485WireParser, RoundTripsEveryLength) {
  WireParser p;
  for (unsigned len : {0u, 1u, 2u, 100u, 255u}) {
    Frame f{0x33, 0x10, 0x01, Bytes(len)};
    for (unsigned i = 0; i < len; ++i) f.data[i] = static_cast<std::uint8_t>(i * 7);
    EXPECT_EQ(feed_all(p, encode_wire_frame(f)), WireParser::Result::frame) << len;
    EXPECT_EQ(p.frame(), f);
  }
}

TEST(Rs485WireParser, BadCrcNoiseAndResynchronisation) {
  WireParser p;
  Bytes wire = encode_wire_frame({0x01, 0x02, 0x00, {0x09}});
  wire.back() ^= 0x01;
  EXPECT_EQ(feed_all(p, wire), WireParser::Result::bad_crc);
  EXPECT_EQ(p.feed(0x55, false), WireParser::Result::noise);
  // A frame cut short by a new address character: the new one still arrives.
  const Bytes good = encode_wire_frame({0x07, 0x01, 0x01, {0x01, 0x02}});
  p.feed(0x07, true);
  p.feed(0x01, false);
  EXPECT_EQ(feed_all(p, good), WireParser::Result::frame);
  EXPECT_EQ(p.truncated(), 1u);
  EXPECT_EQ(p.frame().data, (Bytes{0x01, 0x02}));
}

}  // namespace
}  // namespace advee::rs485
