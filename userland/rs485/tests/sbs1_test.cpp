// SPDX-License-Identifier: GPL-2.0
#include "advee/rs485/devices/sbs1.hpp"

#include <gtest/gtest.h>

#include <numbers>

#include "advee/rs485/fake_transport.hpp"

namespace advee::rs485 {
namespace {

using Bytes = std::vector<std::uint8_t>;

TEST(Rs485Sbs1, BearingsInRadiansWithQuality) {
  // id 3 at 0.00 deg q 200; id 7 at 90.00 deg (9000 = 0x2328) q 5;
  // id 9 at 359.99 deg (35999 = 0x8C9F) q 0.
  auto b = Sbs1::decode_beacons(Bytes{3, 3, 0, 0, 200, 7, 0x28, 0x23, 5, 9, 0x9F, 0x8C, 0});
  ASSERT_TRUE(b) << b.error().message();
  ASSERT_EQ(b->size(), 3u);
  EXPECT_EQ((*b)[0].id, 3);
  EXPECT_DOUBLE_EQ((*b)[0].bearing_rad, 0.0);
  EXPECT_EQ((*b)[0].quality, 200);
  EXPECT_EQ((*b)[1].id, 7);
  EXPECT_DOUBLE_EQ((*b)[1].bearing_rad, std::numbers::pi / 2);
  EXPECT_EQ((*b)[1].quality, 5);
  EXPECT_NEAR((*b)[2].bearing_rad, 2 * std::numbers::pi * 35999 / 36000, 1e-12);
  EXPECT_LT((*b)[2].bearing_rad, 2 * std::numbers::pi);
}

TEST(Rs485Sbs1, NoBeaconSeenIsAnEmptyList) {
  auto b = Sbs1::decode_beacons(Bytes{0});
  ASSERT_TRUE(b);
  EXPECT_TRUE(b->empty());
}

TEST(Rs485Sbs1, MalformedDataIsABadResponse) {
  const Bytes bad[] = {{}, {1}, {1, 3, 0, 0}, {1, 3, 0, 0, 1, 9}, {2, 3, 0, 0, 1},
                       {1, 3, 0xA0, 0x8C, 1} /* 36000: out of range */, {1, 3, 0xFF, 0xFF, 1}};
  for (const auto& b : bad) EXPECT_EQ(Sbs1::decode_beacons(b).error(), Outcome::bad_response) << b.size();
}

TEST(Rs485Sbs1, SetBeaconIdsSendsTheIds) {
  FakeTransport t([](const Request&) { return FakeTransport::ack(); });
  Sbs1 s(t, 0x12);
  const Bytes ids{1, 4, 9};
  EXPECT_FALSE(s.set_beacon_ids(ids));
  ASSERT_EQ(t.requests().size(), 1u);
  EXPECT_EQ(t.requests()[0].instr, sbs1::instr::kSetBeaconIds);
  EXPECT_EQ(t.requests()[0].data, ids);
  EXPECT_EQ(s.set_beacon_ids(Bytes(256)), std::errc::invalid_argument);
  EXPECT_EQ(t.requests().size(), 1u);
}

TEST(Rs485Sbs1, DebugDataIsOpaque) {
  FakeTransport t([](const Request&) { return FakeTransport::ack({1, 2, 3}); });
  EXPECT_EQ(*Sbs1(t, 1).debug_data(), (Bytes{1, 2, 3}));
}

}  // namespace
}  // namespace advee::rs485
