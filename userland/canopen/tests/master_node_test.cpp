// SPDX-License-Identifier: GPL-2.0
// The master as a node (issue 23 item 4): its own dictionary served by SDO
// (0x1000, 0x1001, 0x1016, 0x1017, 0x1018), writes to 0x1016/0x1017 acting
// on its heartbeat consumer and producer, its EMCY; silent while it is no
// node. A second client on the virtual bus plays the tool; manual clock.
#include <gtest/gtest.h>

#include "advee/canopen/master.hpp"
#include "advee/canopen/virtual_bus.hpp"

namespace advee::canopen {
namespace {

using namespace std::chrono_literals;

constexpr std::uint8_t kMasterNode = 0x7F;

MasterConfig node_config(Duration heartbeat) {
  MasterConfig c;
  c.heartbeat_period = heartbeat;
  c.identity = {0xAD, 0x0101, 0x00020003, 0x1234};
  return c;
}

class MasterNodeTest : public testing::Test {
 protected:
  ManualClock clock;
  VirtualBus bus;
  std::vector<CanFrame> seen;  // by the tool's port
  std::size_t master_port = bus.attach([this](const CanFrame& f) { master->handle(f); });
  std::size_t tool_port = bus.attach([this](const CanFrame& f) {
    seen.push_back(f);
    tool.handle(f);
  });
  SdoClient tool{kMasterNode, bus.sender(tool_port), clock.fn(), 100ms};
  std::unique_ptr<Master> master = make(100ms);

  // Its boot-up and first heartbeat are on the bus when this returns.
  std::unique_ptr<Master> make(Duration heartbeat) {
    auto m = std::make_unique<Master>(node_config(heartbeat), bus.sender(master_port), clock.fn());
    bus.deliver();
    return m;
  }
  // The value read, or the abort code as an error.
  std::pair<std::error_code, std::uint32_t> read32(std::uint16_t index, std::uint8_t sub) {
    std::pair<std::error_code, std::uint32_t> got{make_error_code(SdoAbort::kGeneral), 0};
    tool.upload(index, sub, [&](const SdoResult& r) {
      got.first = r.error();
      std::vector<std::uint8_t> d = r.data;  // 1, 2 or 4 bytes
      d.resize(4);
      if (r.ok()) got.second = load_le<std::uint32_t>(d);
    });
    bus.deliver();
    return got;
  }
  std::error_code write32(std::uint16_t index, std::uint8_t sub, std::uint32_t v) {
    std::error_code ec = make_error_code(SdoAbort::kGeneral);
    tool.write<std::uint32_t>(index, sub, v, [&](const SdoResult& r) { ec = r.error(); });
    bus.deliver();
    return ec;
  }
  std::error_code write16(std::uint16_t index, std::uint8_t sub, std::uint16_t v) {
    std::error_code ec = make_error_code(SdoAbort::kGeneral);
    tool.write<std::uint16_t>(index, sub, v, [&](const SdoResult& r) { ec = r.error(); });
    bus.deliver();
    return ec;
  }
  // Heartbeats of the master seen while the clock runs `span` in 1 ms steps.
  int heartbeats_during(Duration span) {
    seen.clear();
    for (auto t = Duration{}; t < span; t += 1ms) {
      clock.advance(1ms);
      master->poll();
      bus.deliver();
    }
    int n = 0;
    for (const CanFrame& f : seen) n += f.id == 0x700u + kMasterNode;
    return n;
  }
};

TEST_F(MasterNodeTest, AnswersItsDeviceTypeIdentityAndHeartbeatTime) {
  const std::vector<std::pair<std::pair<std::uint16_t, std::uint8_t>, std::uint32_t>> want = {
      {{0x1000, 0}, 0},      {{0x1001, 0}, 0},          {{0x1017, 0}, 100},   {{0x1018, 0}, 4},
      {{0x1018, 1}, 0xAD},   {{0x1018, 2}, 0x0101},     {{0x1018, 3}, 0x00020003},
      {{0x1018, 4}, 0x1234}, {{0x1016, 0}, kHeartbeatConsumers}, {{0x1016, 1}, 0}};
  for (const auto& [object, value] : want) {
    const auto [ec, v] = read32(object.first, object.second);
    EXPECT_FALSE(ec) << std::hex << object.first << ":" << int(object.second) << " " << ec.message();
    EXPECT_EQ(v, value) << std::hex << object.first << ":" << int(object.second);
  }
  EXPECT_EQ(read32(0x1018, 5).first, make_error_code(SdoAbort::kNoSubindex));
  EXPECT_EQ(write32(0x1018, 1, 1), make_error_code(SdoAbort::kReadOnly));
}

TEST_F(MasterNodeTest, WritingTheProducerTimeChangesItsHeartbeat) {
  EXPECT_EQ(heartbeats_during(1000ms), 10);
  ASSERT_FALSE(write16(0x1017, 0, 20));
  EXPECT_EQ(master->heartbeat_period(), 20ms);
  // (The heartbeat a new period sends at once went out during the write.)
  EXPECT_EQ(heartbeats_during(1000ms), 50);
  ASSERT_FALSE(write16(0x1017, 0, 0));
  EXPECT_EQ(heartbeats_during(1000ms), 0);
  master->set_heartbeat_period(50ms);
  EXPECT_EQ(read32(0x1017, 0).second, 50u) << "0x1017 follows set_heartbeat_period()";
}

TEST_F(MasterNodeTest, AConsumerEntryWatchesItsNode) {
  std::vector<HeartbeatUpdate> events;
  Registration r = master->add_heartbeat_listener([&](const HeartbeatUpdate& u) { events.push_back(u); });
  ASSERT_FALSE(write32(0x1016, 1, (3u << 16) | 50));
  bus.sender(tool_port)(heartbeat_frame(3, NmtState::kOperational));
  bus.deliver();
  clock.advance(49ms);
  master->poll();
  EXPECT_FALSE(master->heartbeat_consumer().lost(3));
  clock.advance(1ms);
  master->poll();
  EXPECT_TRUE(master->heartbeat_consumer().lost(3));
  ASSERT_FALSE(events.empty());
  EXPECT_EQ(events.back().event, HeartbeatEvent::kLost);
  EXPECT_EQ(events.back().node, 3);
  // A second entry for node 3 is refused; the entry rewritten to node 4
  // stops watching node 3.
  EXPECT_EQ(write32(0x1016, 2, (3u << 16) | 80), make_error_code(SdoAbort::kParamIncompatible));
  EXPECT_EQ(write32(0x1016, 2, 0x01000000u | (4u << 16) | 80), make_error_code(SdoAbort::kInvalidValue));
  ASSERT_FALSE(write32(0x1016, 1, (4u << 16) | 80));
  bus.sender(tool_port)(heartbeat_frame(3, NmtState::kOperational));
  bus.deliver();
  events.clear();
  clock.advance(1s);
  master->poll();
  EXPECT_FALSE(master->heartbeat_consumer().lost(3)) << "node 3 no longer watched";
}

TEST_F(MasterNodeTest, EmcySetsTheErrorRegister) {
  seen.clear();
  master->send_emcy(0x6100, 0x01, {1, 2, 3, 4, 5});
  bus.deliver();
  ASSERT_EQ(seen.size(), 1u);
  EXPECT_EQ(seen[0], make_frame(0x0FF, {0x00, 0x61, 0x01, 1, 2, 3, 4, 5}));
  EXPECT_EQ(read32(0x1001, 0).second, 1u);
  master->send_emcy(0x0000, 0x00);
  EXPECT_EQ(read32(0x1001, 0).second, 0u);
}

TEST_F(MasterNodeTest, OwnErrorsAreSentOnceWithTheRegisterOfAllActiveErrors) {
  seen.clear();
  master->set_error(kEmcyHeartbeatError, true);
  master->set_error(kEmcyHeartbeatError, true);  // no change: no frame
  bus.deliver();
  ASSERT_EQ(seen.size(), 1u);
  EXPECT_EQ(seen[0], make_frame(0x0FF, {0x30, 0x81, 0x11, 0, 0, 0, 0, 0})) << "generic + communication";
  EXPECT_EQ(read32(0x1001, 0).second, 0x11u);
  seen.clear();
  master->set_error(0x4210, true);  // a temperature error on top
  master->set_error(kEmcyHeartbeatError, false);
  bus.deliver();
  ASSERT_EQ(seen.size(), 2u);
  EXPECT_EQ(seen[0], make_frame(0x0FF, {0x10, 0x42, 0x19, 0, 0, 0, 0, 0}));
  EXPECT_EQ(seen[1], make_frame(0x0FF, {0x00, 0x00, 0x09, 0, 0, 0, 0, 0}))
      << "the reset carries the register of the error still active";
  EXPECT_TRUE(master->error_active(0x4210));
  EXPECT_FALSE(master->error_active(kEmcyHeartbeatError));
  seen.clear();
  master->set_error(kEmcyHeartbeatError, false);  // not active: no frame
  master->set_error(0, true);                      // code 0 is no error
  master->set_error(0x4210, false);
  bus.deliver();
  ASSERT_EQ(seen.size(), 1u);
  EXPECT_EQ(seen[0], make_frame(0x0FF, {0, 0, 0, 0, 0, 0, 0, 0}));
  EXPECT_EQ(read32(0x1001, 0).second, 0u);
}

TEST_F(MasterNodeTest, AStoppedMasterSendsNoEmcyButKeepsItsRegister) {
  master->set_nmt_state(NmtState::kStopped);
  seen.clear();
  master->set_error(kEmcyCanErrorPassive, true);
  bus.deliver();
  for (const CanFrame& f : seen) EXPECT_NE(f.id, 0x080u + kMasterNode) << "EMCY while stopped";
  EXPECT_EQ(master->error_register(), 0x11);
  master->set_nmt_state(NmtState::kOperational);
  EXPECT_EQ(read32(0x1001, 0).second, 0x11u);
}

TEST(ErrorRegister, BitsFollowTheErrorClass) {
  EXPECT_EQ(error_register_bits(0x0000), 0x00);
  EXPECT_EQ(error_register_bits(0x1000), 0x01);
  EXPECT_EQ(error_register_bits(0x2310), 0x03);
  EXPECT_EQ(error_register_bits(0x3210), 0x05);
  EXPECT_EQ(error_register_bits(0x4310), 0x09);
  EXPECT_EQ(error_register_bits(0x8120), 0x11);
  EXPECT_EQ(error_register_bits(0x8210), 0x11);
  EXPECT_EQ(error_register_bits(0x8310), 0x01);
  EXPECT_EQ(error_register_bits(0xFF01), 0x81);
}

TEST_F(MasterNodeTest, ASilentMasterServesNoSdo) {
  master = make(Duration{});
  seen.clear();
  std::error_code ec;
  tool.upload(0x1000, 0, [&](const SdoResult& r) { ec = r.error(); });
  bus.deliver();
  for (const CanFrame& f : seen) EXPECT_NE(f.id, 0x580u + kMasterNode) << "a silent master answered";
  clock.advance(100ms);
  tool.poll();
  EXPECT_EQ(ec, make_error_code(SdoAbort::kTimeout));
}

}  // namespace
}  // namespace advee::canopen
