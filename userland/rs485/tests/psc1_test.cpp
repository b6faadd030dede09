// SPDX-License-Identifier: GPL-2.0
#include "advee/rs485/devices/psc1.hpp"

#include <gtest/gtest.h>

#include "advee/rs485/fake_transport.hpp"

namespace advee::rs485 {
namespace {

using Bytes = std::vector<std::uint8_t>;
constexpr std::uint8_t kEvent = response_flag::kEvent;

TEST(Rs485Psc1, CurrentsInAmperesWithNoSensor) {
  Bytes data;
  const std::uint16_t raw[8] = {0, 1, 1500, 0xFFFF, 0xFFFE, 250, 0xFFFF, 10};
  for (auto v : raw) data.insert(data.end(), {static_cast<std::uint8_t>(v), static_cast<std::uint8_t>(v >> 8)});
  auto c = Psc1::decode_currents(data);
  ASSERT_TRUE(c);
  EXPECT_DOUBLE_EQ(*(*c)[0], 0.0);
  EXPECT_DOUBLE_EQ(*(*c)[1], 0.001);
  EXPECT_DOUBLE_EQ(*(*c)[2], 1.5);
  EXPECT_FALSE((*c)[3]);
  EXPECT_DOUBLE_EQ(*(*c)[4], 65.534);
  EXPECT_FALSE((*c)[6]);
  EXPECT_EQ(Psc1::decode_currents(Bytes(15)).error(), Outcome::bad_response);
  EXPECT_EQ(Psc1::decode_currents(Bytes(17)).error(), Outcome::bad_response);
  EXPECT_EQ(Psc1::decode_currents(Bytes{}).error(), Outcome::bad_response);
}

TEST(Rs485Psc1, PowerStatusGetAndSet) {
  std::uint8_t status = 0x01;
  FakeTransport t([&](const Request& r) {
    if (r.instr == psc1::instr::kSetPowerStatus) {
      EXPECT_EQ(r.data.size(), 2u);
      status = static_cast<std::uint8_t>((status & ~r.data[0]) | (r.data[1] & r.data[0]));
    }
    return FakeTransport::ack({status});
  });
  Psc1 p(t, 0x30);
  EXPECT_EQ(*p.power_status(), 0x01);
  EXPECT_EQ(*p.set_power_status(0x81, 0x80), 0x80);
  EXPECT_EQ(t.requests().back().data, (Bytes{0x81, 0x80}));
  EXPECT_EQ(Psc1::decode_power_status(Bytes{}).error(), Outcome::bad_response);
  EXPECT_EQ(Psc1::decode_power_status(Bytes{1, 2}).error(), Outcome::bad_response);
}

TEST(Rs485Psc1, DecodesEventsAndRejectsMalformedOnes) {
  auto pause = Psc1::decode_event({0x30, psc1::instr::kPauseEvent, kEvent, {1, 0x03}});
  ASSERT_TRUE(pause);
  EXPECT_EQ(std::get<PauseEvent>(*pause), (PauseEvent{true, 0x03}));
  auto power = Psc1::decode_event({0x30, psc1::instr::kPowerEvent, kEvent, {0xF0}});
  ASSERT_TRUE(power);
  EXPECT_EQ(std::get<PowerEvent>(*power), (PowerEvent{0xF0}));
  const Frame bad[] = {
      {0x30, psc1::instr::kPauseEvent, 0x01, {1, 3}},    // no EVENT flag: a response
      {0x30, psc1::instr::kPauseEvent, kEvent, {2, 3}},  // engaged not 0/1
      {0x30, psc1::instr::kPauseEvent, kEvent, {1}},
      {0x30, psc1::instr::kPauseEvent, kEvent, {1, 2, 3}},
      {0x30, psc1::instr::kPowerEvent, kEvent, {}},
      {0x30, psc1::instr::kPowerEvent, kEvent, {1, 2}},
      {0x30, 0x42, kEvent, {1}},
  };
  for (const auto& f : bad) EXPECT_EQ(Psc1::decode_event(f).error(), Outcome::bad_response);
}

TEST(Rs485Psc1, EventCallbacksGetOnlyTheirEventsFromTheirNode) {
  FakeTransport t;
  Psc1 p(t, 0x30);
  std::vector<PauseEvent> pauses;
  std::vector<PowerEvent> powers;
  auto s1 = p.on_pause([&](const PauseEvent& e) { pauses.push_back(e); });
  auto s2 = p.on_power([&](const PowerEvent& e) { powers.push_back(e); });
  t.inject_event({0x30, psc1::instr::kPauseEvent, kEvent, {1, 0x01}});
  t.inject_event({0x30, psc1::instr::kPowerEvent, kEvent, {0x0F}});
  t.inject_event({0x31, psc1::instr::kPowerEvent, kEvent, {0xFF}});  // another node
  t.inject_event({0x30, psc1::instr::kPowerEvent, kEvent, {}});      // malformed
  t.inject_event({0x30, psc1::instr::kPauseEvent, kEvent, {0, 0x00}});
  ASSERT_EQ(pauses.size(), 2u);
  EXPECT_EQ(pauses[0], (PauseEvent{true, 0x01}));
  EXPECT_EQ(pauses[1], (PauseEvent{false, 0x00}));
  ASSERT_EQ(powers.size(), 1u);
  EXPECT_EQ(powers[0].status, 0x0F);
  s1.reset();
  t.inject_event({0x30, psc1::instr::kPauseEvent, kEvent, {1, 0x02}});
  EXPECT_EQ(pauses.size(), 2u);
}

}  // namespace
}  // namespace advee::rs485
