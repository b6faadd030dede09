// SPDX-License-Identifier: GPL-2.0
// Node guarding: RTR timing, toggle checking, life time, and the simulated
// drive answering it.
#include "advee/canopen/node_guarding.hpp"

#include <gtest/gtest.h>

#include "advee/canopen/master.hpp"
#include "advee/canopen/sim/drive_sim.hpp"
#include "advee/canopen/virtual_bus.hpp"

namespace advee::canopen {
namespace {

using namespace std::chrono_literals;

class NodeGuardingTest : public testing::Test {
 protected:
  ManualClock clock;
  std::vector<CanFrame> sent;
  std::vector<HeartbeatUpdate> events;
  NodeGuarding guarding{[this](const CanFrame& f) { sent.push_back(f); }, clock.fn(),
                        [this](const HeartbeatUpdate& u) { events.push_back(u); }};

  void tick(Duration d) {
    clock.advance(d);
    guarding.poll();
  }
  static CanFrame reply(std::uint8_t b) { return make_frame(0x705, {b}); }
};

TEST_F(NodeGuardingTest, SendsAnRtrEveryGuardTime) {
  guarding.guard(5, 100ms, 3);
  ASSERT_EQ(sent.size(), 1u);
  EXPECT_EQ(to_string(sent[0]), "705#R");
  EXPECT_EQ(sent[0].len, 1);
  tick(99ms);
  EXPECT_EQ(sent.size(), 1u);
  tick(1ms);
  EXPECT_EQ(sent.size(), 2u);
}

TEST_F(NodeGuardingTest, AlternatingRepliesKeepTheNodeAliveAndReportItsState) {
  guarding.guard(5, 100ms, 3);
  for (int i = 0; i < 10; ++i) {
    EXPECT_TRUE(guarding.handle(reply(static_cast<std::uint8_t>(0x05 | (i % 2 ? 0x80 : 0)))));
    tick(100ms);
  }
  EXPECT_FALSE(guarding.lost(5));
  ASSERT_EQ(events.size(), 1u);
  EXPECT_EQ(events[0].event, HeartbeatEvent::kStateChanged);
  EXPECT_EQ(events[0].state, NmtState::kOperational);
  EXPECT_EQ(guarding.toggle_errors(), 0u);
}

TEST_F(NodeGuardingTest, NoValidReplyWithinTheLifeTimeIsALoss) {
  guarding.guard(5, 100ms, 3);
  guarding.handle(reply(0x05));
  tick(100ms);
  guarding.handle(reply(0x05));  // toggle not alternated: does not count
  EXPECT_EQ(guarding.toggle_errors(), 1u);
  tick(199ms);
  EXPECT_FALSE(guarding.lost(5));
  tick(1ms);
  EXPECT_TRUE(guarding.lost(5));
  ASSERT_FALSE(events.empty());
  EXPECT_EQ(events.back().event, HeartbeatEvent::kLost);
  guarding.handle(reply(0x85));
  EXPECT_EQ(events.back().event, HeartbeatEvent::kResumed);
}

TEST_F(NodeGuardingTest, UnguardedNodesAndHeartbeatsOfOthersAreNotTaken) {
  guarding.guard(5, 100ms, 3);
  EXPECT_FALSE(guarding.handle(make_frame(0x706, {0x05})));
  guarding.guard(5, 0ms, 0);
  EXPECT_FALSE(guarding.handle(reply(0x05)));
}

TEST(NodeGuardingWithDriveTest, SimulatedDriveAnswersAndSilenceIsDetected) {
  ManualClock clock;
  VirtualBus bus;
  std::unique_ptr<Master> master;
  std::unique_ptr<sim::SimulatedDrive> drive;
  const auto mp = bus.attach([&](const CanFrame& f) { master->handle(f); });
  const auto dp = bus.attach([&](const CanFrame& f) { drive->handle(f); });
  master = std::make_unique<Master>(MasterConfig{}, bus.sender(mp), clock.fn());
  drive = std::make_unique<sim::SimulatedDrive>(sim::DriveSimConfig{3, sim::DriveProfile::kIcla}, bus.sender(dp),
                                                clock.fn());
  std::vector<HeartbeatUpdate> events;
  const Registration listener = master->add_heartbeat_listener([&](const HeartbeatUpdate& u) { events.push_back(u); });
  drive->power_on();
  bus.deliver();
  events.clear();
  master->node_guarding().guard(3, 50ms, 2);
  auto run = [&](Duration d) {
    for (auto end = clock.now() + d; clock.now() < end;) {
      clock.advance(1ms);
      master->poll();
      drive->poll();
      bus.deliver();
    }
  };
  run(1s);
  EXPECT_FALSE(master->node_guarding().lost(3));
  EXPECT_EQ(master->node_guarding().toggle_errors(), 0u);
  ASSERT_EQ(events.size(), 1u);
  EXPECT_EQ(events[0].state, NmtState::kPreOperational);
  drive->faults().heartbeat_silent = true;
  run(99ms);
  EXPECT_FALSE(master->node_guarding().lost(3));
  run(60ms);
  EXPECT_TRUE(master->node_guarding().lost(3));
}

}  // namespace
}  // namespace advee::canopen
