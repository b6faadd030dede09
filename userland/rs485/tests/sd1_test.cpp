// SPDX-License-Identifier: GPL-2.0
#include "advee/rs485/devices/sd1.hpp"

#include <gtest/gtest.h>

#include "advee/rs485/fake_transport.hpp"

namespace advee::rs485 {
namespace {

using Bytes = std::vector<std::uint8_t>;

TEST(Rs485Sd1, SrfInMetresWithNoEchoAndZero) {
  // 3 readings: 0 cm (a real zero), 0xFFFF (no echo), 0x0123 = 291 cm.
  auto r = Sd1::decode_srf(Bytes{3, 0x00, 0x00, 0xFF, 0xFF, 0x23, 0x01});
  ASSERT_TRUE(r);
  ASSERT_EQ(r->size(), 3u);
  ASSERT_TRUE((*r)[0]);
  EXPECT_DOUBLE_EQ(*(*r)[0], 0.0);
  EXPECT_FALSE((*r)[1]);
  EXPECT_DOUBLE_EQ(*(*r)[2], 2.91);
  // 0xFFFE is the largest real reading, not "no echo".
  EXPECT_DOUBLE_EQ(*(*Sd1::decode_srf(Bytes{1, 0xFE, 0xFF}))[0], 655.34);
}

TEST(Rs485Sd1, IrInMetresWithOutOfRange) {
  // 0 = out of range, 1 = 2 mm, 255 = 510 mm.
  auto r = Sd1::decode_ir(Bytes{3, 0, 1, 255});
  ASSERT_TRUE(r);
  ASSERT_EQ(r->size(), 3u);
  EXPECT_FALSE((*r)[0]);
  EXPECT_DOUBLE_EQ(*(*r)[1], 0.002);
  EXPECT_DOUBLE_EQ(*(*r)[2], 0.510);
}

TEST(Rs485Sd1, EmptyListsAreValid) {
  EXPECT_TRUE(Sd1::decode_srf(Bytes{0})->empty());
  EXPECT_TRUE(Sd1::decode_ir(Bytes{0})->empty());
  auto both = Sd1::decode_both(Bytes{0, 0});
  ASSERT_TRUE(both);
  EXPECT_TRUE(both->srf_m.empty() && both->ir_m.empty());
}

TEST(Rs485Sd1, BothAtOnce) {
  // 8 SRF (first 100 cm, rest no echo), 2 IR (50 = 100 mm, 0).
  Bytes data{8, 100, 0};
  for (int i = 1; i < 8; ++i) data.insert(data.end(), {0xFF, 0xFF});
  data.insert(data.end(), {2, 50, 0});
  FakeTransport t([&](const Request& r) {
    EXPECT_EQ(r.instr, sd1::instr::kGetBoth);
    return FakeTransport::ack(data);
  });
  auto d = Sd1(t, 0x10).distances();
  ASSERT_TRUE(d) << d.error().message();
  ASSERT_EQ(d->srf_m.size(), 8u);
  EXPECT_DOUBLE_EQ(*d->srf_m[0], 1.0);
  for (int i = 1; i < 8; ++i) EXPECT_FALSE(d->srf_m[i]);
  ASSERT_EQ(d->ir_m.size(), 2u);
  EXPECT_DOUBLE_EQ(*d->ir_m[0], 0.1);
  EXPECT_FALSE(d->ir_m[1]);
}

TEST(Rs485Sd1, ShortLongAndGarbageDataAreBadResponses) {
  const Bytes bad_srf[] = {{}, {1}, {1, 0}, {1, 0, 0, 0}, {2, 0, 0, 0}, {255}};
  for (const auto& b : bad_srf) EXPECT_EQ(Sd1::decode_srf(b).error(), Outcome::bad_response) << b.size();
  const Bytes bad_ir[] = {{}, {2, 1}, {1, 1, 1}, {200}};
  for (const auto& b : bad_ir) EXPECT_EQ(Sd1::decode_ir(b).error(), Outcome::bad_response) << b.size();
  const Bytes bad_both[] = {{}, {0}, {1, 0, 0}, {0, 1}, {0, 1, 5, 5}, {0, 0, 0}, {1, 0, 0, 0, 0}};
  for (const auto& b : bad_both) EXPECT_EQ(Sd1::decode_both(b).error(), Outcome::bad_response) << b.size();
  // Every prefix of a good response is rejected, never read past its end.
  const Bytes good{2, 1, 0, 2, 0, 2, 7, 8};
  ASSERT_TRUE(Sd1::decode_both(good));
  for (std::size_t n = 0; n < good.size(); ++n)
    EXPECT_FALSE(Sd1::decode_both(std::span(good).first(n))) << n;
}

TEST(Rs485Sd1, PauseSources) {
  FakeTransport t([](const Request& r) {
    if (r.instr == sd1::instr::kGetPauseSource) return FakeTransport::ack({0x05});
    if (r.instr == sd1::instr::kClearPauseSource) return FakeTransport::ack();
    return FakeTransport::fail(Outcome::unknown_instruction);
  });
  Sd1 d(t, 0x10);
  auto p = d.pause_sources();
  ASSERT_TRUE(p);
  EXPECT_TRUE(p->front_bumper());
  EXPECT_FALSE(p->rear_bumper());
  EXPECT_TRUE(p->ground_sensor());
  EXPECT_FALSE(p->ultrasonic_proximity());
  EXPECT_FALSE(d.clear_pause_sources());
  EXPECT_EQ(Sd1::decode_pause_sources(Bytes{}).error(), Outcome::bad_response);
  EXPECT_EQ(Sd1::decode_pause_sources(Bytes{1, 2}).error(), Outcome::bad_response);
  EXPECT_FALSE(Sd1::decode_pause_sources(Bytes{0})->any());
}

}  // namespace
}  // namespace advee::rs485
