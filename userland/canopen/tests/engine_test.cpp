// SPDX-License-Identifier: GPL-2.0
// NMT, heartbeat, SYNC/TIME, EMCY and the master's demultiplexing, driven
// through the virtual bus with a manual clock.
#include <gtest/gtest.h>

#include "advee/canopen/master.hpp"
#include "advee/canopen/virtual_bus.hpp"

namespace advee::canopen {
namespace {

using namespace std::chrono_literals;

class EngineTest : public testing::Test {
 protected:
  ManualClock clock;
  VirtualBus bus;
  std::vector<CanFrame> seen;  // what the rest of the bus sees from the master
  std::size_t master_port = bus.attach([this](const CanFrame& f) { master.handle(f); });
  std::size_t node_port = bus.attach([this](const CanFrame& f) { seen.push_back(f); });
  Master master{MasterConfig{0x7F, 100ms, {}}, bus.sender(master_port), clock.fn()};
  std::vector<HeartbeatUpdate> hb;
  Registration hb_listener;

  void SetUp() override {
    hb_listener = master.add_heartbeat_listener([this](const HeartbeatUpdate& u) { hb.push_back(u); });
  }
  void from_node(const CanFrame& f) {
    bus.sender(node_port)(f);
    bus.deliver();
  }
  void tick(Duration d) {
    clock.advance(d);
    master.poll();
    bus.deliver();
  }
};

TEST_F(EngineTest, NmtCommandFramesFollowCia301) {
  master.nmt(NmtCommand::kStart, 5);
  master.nmt(NmtCommand::kResetNode, 0);
  master.nmt(NmtCommand::kEnterPreOperational, 3);
  bus.deliver();
  ASSERT_EQ(seen.size(), 3u);
  EXPECT_EQ(to_string(seen[0]), "000#0105");
  EXPECT_EQ(to_string(seen[1]), "000#8100");
  EXPECT_EQ(to_string(seen[2]), "000#8003");
}

TEST_F(EngineTest, HeartbeatConsumerReportsBootStateAndLossAtTheConsumerTime) {
  master.heartbeat_consumer().monitor(5, 300ms);
  from_node(heartbeat_frame(5, NmtState::kBootUp));
  from_node(heartbeat_frame(5, NmtState::kPreOperational));
  ASSERT_EQ(hb.size(), 2u);
  EXPECT_EQ(hb[0].event, HeartbeatEvent::kBootUp);
  EXPECT_EQ(hb[1].event, HeartbeatEvent::kStateChanged);
  EXPECT_EQ(hb[1].state, NmtState::kPreOperational);
  EXPECT_EQ(master.heartbeat_consumer().state(5), NmtState::kPreOperational);
  from_node(heartbeat_frame(5, NmtState::kPreOperational));
  EXPECT_EQ(hb.size(), 2u) << "the same state again is not news";

  tick(299ms);
  EXPECT_EQ(hb.size(), 2u);
  EXPECT_FALSE(master.heartbeat_consumer().lost(5));
  tick(1ms);
  ASSERT_EQ(hb.size(), 3u);
  EXPECT_EQ(hb[2].event, HeartbeatEvent::kLost);
  tick(1s);
  EXPECT_EQ(hb.size(), 3u) << "loss is reported once";

  from_node(heartbeat_frame(5, NmtState::kOperational));
  ASSERT_EQ(hb.size(), 5u);
  EXPECT_EQ(hb[3].event, HeartbeatEvent::kResumed);
  EXPECT_EQ(hb[4].state, NmtState::kOperational);
}

TEST_F(EngineTest, HeartbeatMonitoringStartsWithTheFirstHeartbeat) {
  master.heartbeat_consumer().monitor(9, 100ms);
  tick(1s);
  EXPECT_TRUE(hb.empty());
  EXPECT_FALSE(master.next_deadline().has_value());
}

TEST_F(EngineTest, HeartbeatDeadlineIsExposedForTheEventLoop) {
  master.heartbeat_consumer().monitor(5, 250ms);
  from_node(heartbeat_frame(5, NmtState::kOperational));
  ASSERT_TRUE(master.next_deadline().has_value());
  EXPECT_EQ(*master.next_deadline(), clock.now() + 250ms);
}

TEST_F(EngineTest, HeartbeatProducerSendsAtOnceAndThenEveryPeriod) {
  master.set_heartbeat_period(100ms);
  bus.deliver();
  ASSERT_EQ(seen.size(), 2u);
  EXPECT_EQ(to_string(seen[0]), "77F#00");  // boot-up
  EXPECT_EQ(to_string(seen[1]), "77F#7F");
  tick(99ms);
  EXPECT_EQ(seen.size(), 2u);
  tick(1ms);
  EXPECT_EQ(seen.size(), 3u);
  tick(100ms);
  tick(100ms);
  EXPECT_EQ(seen.size(), 5u);
  master.set_heartbeat_period(0ms);
  tick(1s);
  EXPECT_EQ(seen.size(), 5u);
}

TEST_F(EngineTest, SyncCounterRunsFromOneToOverflowAndWraps) {
  master.sync().start(10ms, 3);
  for (int i = 0; i < 7; ++i) tick(10ms);
  ASSERT_EQ(seen.size(), 7u);
  std::vector<int> counters;
  for (auto& f : seen) {
    EXPECT_EQ(f.id, 0x080u);
    ASSERT_EQ(f.len, 1);
    counters.push_back(f.data[0]);
  }
  EXPECT_EQ(counters, (std::vector<int>{1, 2, 3, 1, 2, 3, 1}));
}

TEST_F(EngineTest, SyncWithoutCounterHasNoData) {
  std::vector<std::uint8_t> callbacks;
  master.sync().on_sync([&](std::uint8_t c) { callbacks.push_back(c); });
  master.sync().start(5ms);
  tick(5ms);
  ASSERT_EQ(seen.size(), 1u);
  EXPECT_EQ(seen[0].len, 0);
  EXPECT_EQ(callbacks, std::vector<std::uint8_t>{0});
  master.sync().stop();
  tick(50ms);
  EXPECT_EQ(seen.size(), 1u);
}

TEST_F(EngineTest, SyncRejectsInvalidCounterOverflow) {
  EXPECT_THROW(master.sync().start(10ms, 1), std::invalid_argument);
  EXPECT_THROW(master.sync().start(10ms, 241), std::invalid_argument);
  EXPECT_NO_THROW(master.sync().start(10ms, 240));
}

TEST_F(EngineTest, SyncSkipsMissedPeriodsInsteadOfBursting) {
  master.sync().start(10ms);
  tick(95ms);
  EXPECT_EQ(seen.size(), 1u);
}

TEST(TimeOfDayTest, RoundTripsAndUsesThe1984Epoch) {
  using namespace std::chrono;
  const system_clock::time_point epoch{seconds(441763200)};
  CanFrame f = time_of_day_frame(epoch + days(1) + milliseconds(1234));
  EXPECT_EQ(to_string(f), "100#D20400000100");
  const auto t = system_clock::time_point(milliseconds(1700000000123));
  EXPECT_EQ(decode_time_of_day(time_of_day_frame(t)), t);
}

TEST(TimeProducerTest, PeriodicTimeCarriesTheWallClock) {
  using namespace std::chrono;
  ManualClock clock;
  system_clock::time_point wall{seconds(441763200) + days(2)};
  std::vector<CanFrame> sent;
  Master m{MasterConfig{}, [&](const CanFrame& f) { sent.push_back(f); }, clock.fn(), [&] { return wall; }};
  m.time_producer().start(1s);
  ASSERT_EQ(sent.size(), 1u);
  EXPECT_EQ(to_string(sent[0]), "100#000000000200");
  wall += 1s;
  clock.advance(999ms);
  m.poll();
  EXPECT_EQ(sent.size(), 1u);
  clock.advance(1ms);
  m.poll();
  ASSERT_EQ(sent.size(), 2u);
  EXPECT_EQ(decode_time_of_day(sent[1]), wall);
  m.time_producer().stop();
  clock.advance(5s);
  m.poll();
  EXPECT_EQ(sent.size(), 2u);
}

TEST_F(EngineTest, EmcyIsDecodedAndSyncIsNotMistakenForIt) {
  std::vector<Emcy> emcy;
  const Registration listener = master.add_emcy_listener([&](const Emcy& e) { emcy.push_back(e); });
  from_node(make_frame(0x080, {1}));
  from_node(make_frame(0x081, {0x10, 0x42, 0x09, 1, 2, 3, 4, 5}));
  ASSERT_EQ(emcy.size(), 1u);
  EXPECT_EQ(emcy[0].node, 1);
  EXPECT_EQ(emcy[0].code, 0x4210);
  EXPECT_EQ(emcy[0].error_register, 0x09);
  EXPECT_EQ(emcy_class(emcy[0].code), "temperature");
  EXPECT_EQ(to_string(emcy[0]), "node 1 EMCY 0x4210 (temperature) register 0x09");
  EXPECT_EQ(emcy_class(0x8130), "monitoring");
  EXPECT_EQ(emcy_class(0x8210), "protocol");
}

TEST_F(EngineTest, PdoListenersGetTheirCobIdOnly) {
  int a = 0, b = 0, other = 0;
  auto sub_a = master.subscribe(0x181, [&](const CanFrame&) { ++a; });
  const auto sub_b = master.subscribe(0x181, [&](const CanFrame&) { ++b; });
  master.set_fallback_listener([&](const CanFrame&) { ++other; });
  from_node(make_frame(0x181, {0x37, 0x02}));
  from_node(make_frame(0x182, {0x37, 0x02}));
  sub_a.reset();
  from_node(make_frame(0x181, {0x37, 0x02}));
  EXPECT_EQ(a, 1);
  EXPECT_EQ(b, 2);
  EXPECT_EQ(other, 1);
}

TEST_F(EngineTest, ObserverSeesFramesTheProtocolObjectsConsume) {
  std::vector<std::string> observed;
  master.set_observer([&](const CanFrame& f) { observed.push_back(to_string(f)); });
  from_node(heartbeat_frame(5, NmtState::kOperational));
  from_node(make_frame(0x085, {0x00, 0x00, 0x00}));
  EXPECT_EQ(observed, (std::vector<std::string>{"705#05", "085#000000"}));
  EXPECT_EQ(hb.size(), 1u) << "and the heartbeat consumer still got its frame";
}

TEST_F(EngineTest, SdoResponsesAreRoutedPerNode) {
  std::vector<int> done;
  master.sdo(2).upload(0x1000, 0, [&](const SdoResult&) { done.push_back(2); });
  master.sdo(3).upload(0x1000, 0, [&](const SdoResult&) { done.push_back(3); });
  bus.deliver();
  EXPECT_EQ(seen.size(), 2u) << "one outstanding transfer per node, nodes in parallel";
  CanFrame r = make_frame(0x583, {0x43, 0x00, 0x10, 0x00, 1, 2, 3, 4});
  from_node(r);
  EXPECT_EQ(done, std::vector<int>{3});
}

TEST_F(EngineTest, BootUpDoesNotCancelTransfersWhoseReplyArrives) {
  std::vector<SdoResult> r;
  auto record = [&](const SdoResult& x) { r.push_back(x); };
  master.sdo(5).upload(0x1000, 0, record);
  master.sdo(5).upload(0x1001, 0, record);
  master.sdo(5).upload(0x1002, 0, record);
  // The answer and then a (repeated) boot-up in one batch: the next request
  // went out after the boot-up reached us, so the node answers it.
  bus.sender(node_port)(make_frame(0x585, {0x43, 0x00, 0x10, 0x00, 1, 0, 0, 0, }));
  bus.sender(node_port)(heartbeat_frame(5, NmtState::kBootUp));
  bus.deliver();
  from_node(make_frame(0x585, {0x43, 0x01, 0x10, 0x00, 2, 0, 0, 0}));
  // A boot-up while a request is outstanding, then its answer.
  from_node(heartbeat_frame(5, NmtState::kBootUp));
  from_node(make_frame(0x585, {0x43, 0x02, 0x10, 0x00, 3, 0, 0, 0}));
  ASSERT_EQ(r.size(), 3u);
  for (const auto& x : r) EXPECT_TRUE(x.ok()) << x.error().message();
  EXPECT_EQ(r[2].data, (std::vector<std::uint8_t>{3, 0, 0, 0}));
}

TEST_F(EngineTest, NextDeadlineIsTheEarliestOfAllTimers) {
  master.set_heartbeat_period(100ms);
  master.sync().start(30ms);
  master.sdo(4).upload(0x1000, 0, nullptr);  // 100 ms SDO timeout
  EXPECT_EQ(*master.next_deadline(), clock.now() + 30ms);
}

TEST(RegistrationTest, EndsWithItsHandleAndMayOutliveTheMaster) {
  ManualClock clock;
  auto master = std::make_unique<Master>(MasterConfig{}, [](const CanFrame&) {}, clock.fn());
  int a = 0, b = 0;
  Registration ra, rb;
  // A removes B while the list is being called: B is not called any more.
  ra = master->add_emcy_listener([&](const Emcy&) {
    ++a;
    rb.reset();
  });
  rb = master->add_emcy_listener([&](const Emcy&) { ++b; });
  master->handle(make_frame(0x081, {0x10, 0x42, 0x09, 0, 0, 0, 0, 0}));
  EXPECT_EQ(a, 1);
  EXPECT_EQ(b, 0);
  ra.reset();
  master->handle(make_frame(0x081, {0x10, 0x42, 0x09, 0, 0, 0, 0, 0}));
  EXPECT_EQ(a, 1);
  Registration late = master->subscribe(0x181, [](const CanFrame&) {});
  master.reset();
  late.reset();  // after the master: nothing to do, nothing touched (ASan)
}

TEST(RegistrationTest, ServiceEndedByAnotherServiceIsNotPolledAgain) {
  ManualClock clock;
  Master master(MasterConfig{}, [](const CanFrame&) {}, clock.fn());
  struct Service final : TimedService {
    std::function<void()> on_poll;
    int polls = 0;
    void poll() override {
      ++polls;
      if (on_poll) on_poll();
    }
    std::optional<TimePoint> deadline() const override { return std::nullopt; }
  };
  auto first = std::make_unique<Service>();
  auto second = std::make_unique<Service>();
  Registration r1 = master.attach(*first);
  auto r2 = std::make_unique<Registration>(master.attach(*second));
  first->on_poll = [&] {
    r2.reset();  // ends the registration and then the service
    second.reset();
  };
  master.poll();  // ASan: second must not be polled after it is gone
  EXPECT_EQ(first->polls, 1);
  r1.reset();
  master.poll();
  EXPECT_EQ(first->polls, 1);
}

}  // namespace
}  // namespace advee::canopen
