// SPDX-License-Identifier: GPL-2.0
// Standard instructions of every device, against a fake transport.
#include "advee/rs485/devices/device.hpp"

#include <gtest/gtest.h>

#include "advee/rs485/devices/psc1.hpp"
#include "advee/rs485/devices/sbs1.hpp"
#include "advee/rs485/devices/sd1.hpp"
#include "advee/rs485/devices/so1.hpp"
#include "advee/rs485/fake_transport.hpp"

namespace advee::rs485 {
namespace {

using Bytes = std::vector<std::uint8_t>;

TEST(Rs485Device, FirmwareVersionOfEveryDriver) {
  FakeTransport t([](const Request& r) {
    EXPECT_EQ(r.instr, standard_instr::kGetFirmwareVersion);
    EXPECT_TRUE(r.data.empty());
    return FakeTransport::ack({r.addr, 7});
  });
  Sd1 sd1(t, 0x10);
  So1 so1(t, 0x11);
  Sbs1 sbs1(t, 0x12);
  Psc1 psc1(t, 0x13);
  for (Device* d : std::initializer_list<Device*>{&sd1, &so1, &sbs1, &psc1}) {
    auto v = d->firmware_version();
    ASSERT_TRUE(v) << v.error().message();
    EXPECT_EQ(*v, (FirmwareVersion{d->address(), 7}));
  }
  EXPECT_EQ(t.requests().size(), 4u);
}

TEST(Rs485Device, FirmwareVersionOfWrongLengthIsABadResponse) {
  for (Bytes data : {Bytes{}, Bytes{1}, Bytes{1, 2, 3}}) {
    FakeTransport t([&](const Request&) { return FakeTransport::ack(data); });
    EXPECT_EQ(Sd1(t, 1).firmware_version().error(), Outcome::bad_response) << data.size();
  }
}

TEST(Rs485Device, OutcomesOfTheBusPassThrough) {
  for (auto o : {Outcome::timeout, Outcome::bad_crc, Outcome::unknown_instruction, Outcome::device_error,
                 Outcome::error}) {
    FakeTransport t([&](const Request&) { return FakeTransport::fail(o); });
    EXPECT_EQ(So1(t, 1).firmware_version().error(), o);
    EXPECT_EQ(So1(t, 1).reset(), o);
  }
}

TEST(Rs485Device, ResetAndBroadcastReset) {
  FakeTransport t([](const Request&) { return FakeTransport::ack(); });
  EXPECT_FALSE(Sbs1(t, 0x20).reset());
  EXPECT_FALSE(broadcast_reset(t));
  const auto reqs = t.requests();
  ASSERT_EQ(reqs.size(), 2u);
  EXPECT_EQ(reqs[0].addr, 0x20);
  EXPECT_EQ(reqs[0].instr, standard_instr::kReset);
  EXPECT_EQ(reqs[1].addr, kBroadcast);
  EXPECT_EQ(reqs[1].instr, standard_instr::kReset);
  EXPECT_FALSE(reqs[1].expects_response());
}

TEST(Rs485Device, CallOptionsReachTheTransport) {
  FakeTransport t([](const Request&) { return FakeTransport::ack({1, 0}); });
  Sd1 d(t, 1);
  ASSERT_TRUE(d.firmware_version({std::chrono::milliseconds(5), 0}));
  const auto r = t.requests().at(0);
  EXPECT_EQ(r.options.timeout, std::chrono::microseconds(5000));
  EXPECT_EQ(r.options.retries, 0u);
}

}  // namespace
}  // namespace advee::rs485
