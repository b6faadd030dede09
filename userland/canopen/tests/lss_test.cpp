// SPDX-License-Identifier: GPL-2.0
// CiA 305 LSS: the master's services against simulated slaves (LssSimNode:
// an LSS slave in front of a simulated drive) on the virtual bus with a
// manual clock; a scripted slave for the answers the simulator never gives.
#include <gtest/gtest.h>

#include <memory>

#include "advee/canopen/lss_master.hpp"
#include "advee/canopen/master.hpp"
#include "advee/canopen/sim/lss_slave.hpp"
#include "advee/canopen/virtual_bus.hpp"

namespace advee::canopen {
namespace {

using namespace std::chrono_literals;
using sim::DriveProfile;
using sim::DriveSimConfig;
using sim::LssSimNode;

constexpr LssMasterConfig kLssConfig{100ms, 10ms};

class LssTest : public testing::Test {
 protected:
  ManualClock clock;
  VirtualBus bus;
  std::size_t master_port = bus.attach([this](const CanFrame& f) { master.handle(f); });
  Master master{MasterConfig{0x7F, 100ms, {}}, bus.sender(master_port), clock.fn()};
  LssMaster lss{master, kLssConfig};
  std::vector<std::unique_ptr<LssSimNode>> nodes;
  std::vector<std::size_t> ports;

  // An EPOS with this serial number; node-ID kLssUnconfigured: none.
  LssSimNode& add_node(std::uint32_t serial, std::uint8_t node_id) {
    DriveSimConfig cfg;
    cfg.profile = DriveProfile::kEpos;
    cfg.serial = serial;
    return add_node(cfg, node_id);
  }
  LssSimNode& add_node(const DriveSimConfig& cfg, std::uint8_t node_id) {
    const std::size_t i = nodes.size();
    ports.push_back(bus.attach([this, i](const CanFrame& f) { nodes[i]->handle(f); }));
    nodes.push_back(std::make_unique<LssSimNode>(cfg, node_id, bus.sender(ports.back()), clock.fn()));
    nodes.back()->power_on();
    bus.deliver();
    return *nodes.back();
  }
  static LssAddress epos(std::uint32_t serial) { return {{0x000000FB, 0x64200000, 0x00010000, serial}}; }

  std::optional<TimePoint> next_deadline() const {
    auto d = master.next_deadline();
    for (const auto& n : nodes)
      if (auto nd = n->deadline(); nd && (!d || *nd < *d)) d = nd;
    return d;
  }
  // Runs bus and clock until `done` or `limit` of simulated time passed;
  // the clock jumps from deadline to deadline.
  template <typename Pred>
  bool run_until(Pred done, Duration limit = 60s) {
    const TimePoint end = clock.now() + limit;
    for (;;) {
      bus.deliver();
      master.poll();
      for (auto& n : nodes) n->poll();
      bus.deliver();
      if (done()) return true;
      const auto d = next_deadline();
      if (!d || *d > end) return false;
      if (*d > clock.now()) clock.advance(*d - clock.now());
    }
  }
  LssResult run(std::function<void(LssCallback)> service) {
    std::optional<LssResult> r;
    service([&r](const LssResult& res) { r = res; });
    EXPECT_TRUE(run_until([&] { return r.has_value(); })) << "the service never ended";
    return r.value_or(LssResult{LssError::kCancelled});
  }
  std::vector<std::string> sent_lss() const {
    std::vector<std::string> out;
    for (const auto& f : bus.log())
      if (f.id == cob::kLssMaster) out.push_back(to_string(f));
    return out;
  }
};

TEST_F(LssTest, FramesFollowCia305) {
  run([&](LssCallback cb) { lss.switch_global(LssMode::kConfiguration, cb); });
  run([&](LssCallback cb) { lss.configure_bit_timing(3, cb); });
  run([&](LssCallback cb) { lss.activate_bit_timing(250ms, cb); });
  run([&](LssCallback cb) { lss.inquire(LssInquiry::kNodeId, cb); });
  run([&](LssCallback cb) { lss.fastscan([cb](const LssFastscanResult& r) { cb(r.result); }); });
  const auto sent = sent_lss();
  ASSERT_GE(sent.size(), 5u);
  EXPECT_EQ(sent[0], "7E5#0401000000000000");
  EXPECT_EQ(sent[1], "7E5#1300030000000000");
  EXPECT_EQ(sent[2], "7E5#15FA000000000000");
  EXPECT_EQ(sent[3], "7E5#5E00000000000000");
  EXPECT_EQ(sent[4], "7E5#5100000000800000") << "fastscan reset: bit-checked 0x80";
}

TEST_F(LssTest, InquireIdentityAndNodeIdOfTheSlaveInConfigurationState) {
  add_node(1234, 5);
  EXPECT_TRUE(run([&](LssCallback cb) { lss.switch_global(LssMode::kConfiguration, cb); }).ok());
  EXPECT_EQ(nodes[0]->lss().mode(), LssMode::kConfiguration);
  const std::uint32_t want[] = {0xFB, 0x64200000, 0x00010000, 1234, 5};
  for (std::uint8_t i = 0; i <= 4; ++i) {
    const auto r = run([&](LssCallback cb) { lss.inquire(static_cast<LssInquiry>(i), cb); });
    EXPECT_TRUE(r.ok()) << describe(r);
    EXPECT_EQ(r.value, want[i]) << "inquiry " << int(i);
    EXPECT_EQ(r.answers, 1u);
  }
  run([&](LssCallback cb) { lss.switch_global(LssMode::kWaiting, cb); });
  EXPECT_EQ(nodes[0]->lss().mode(), LssMode::kWaiting);
}

TEST_F(LssTest, SwitchSelectiveTakesOnlyTheAddressedSlave) {
  add_node(1, 5);
  add_node(2, 6);
  const auto r = run([&](LssCallback cb) { lss.switch_selective(epos(2), cb); });
  EXPECT_TRUE(r.ok()) << describe(r);
  EXPECT_EQ(nodes[0]->lss().mode(), LssMode::kWaiting);
  EXPECT_EQ(nodes[1]->lss().mode(), LssMode::kConfiguration);
  const auto id = run([&](LssCallback cb) { lss.inquire(LssInquiry::kNodeId, cb); });
  EXPECT_TRUE(id.ok());
  EXPECT_EQ(id.value, 6u);
}

TEST_F(LssTest, SwitchSelectiveOfAnUnknownAddressTimesOutAfterTheTimeout) {
  add_node(1, 5);
  const TimePoint start = clock.now();
  const auto r = run([&](LssCallback cb) { lss.switch_selective(epos(99), cb); });
  EXPECT_EQ(r.error, LssError::kTimeout);
  EXPECT_EQ(clock.now() - start, kLssConfig.timeout);
  EXPECT_EQ(nodes[0]->lss().mode(), LssMode::kWaiting);
}

TEST_F(LssTest, ConfigureNodeIdOfAConfiguredNodeTakesEffectAtResetCommunication) {
  add_node(1, 5);
  run([&](LssCallback cb) { lss.switch_selective(epos(1), cb); });
  EXPECT_TRUE(run([&](LssCallback cb) { lss.configure_node_id(9, cb); }).ok());
  run([&](LssCallback cb) { lss.switch_global(LssMode::kWaiting, cb); });
  EXPECT_EQ(nodes[0]->drive()->config().node, 5) << "CiA 305: a node with a node-ID keeps it until reset";
  bus.clear_log();
  master.nmt(NmtCommand::kResetCommunication, 5);
  run_until([] { return false; }, 5ms);
  ASSERT_NE(nodes[0]->drive(), nullptr);
  EXPECT_EQ(nodes[0]->drive()->config().node, 9);
  EXPECT_EQ(to_string(bus.log().back()), "709#00") << "boot-up with the new node-ID";
}

TEST_F(LssTest, ConfigureNodeIdRefusesInvalidIdsWithoutSendingAnything) {
  for (unsigned id : {0u, 128u, 0xFEu}) {
    const auto r = run([&](LssCallback cb) { lss.configure_node_id(static_cast<std::uint8_t>(id), cb); });
    EXPECT_EQ(r.error, LssError::kInvalidArgument) << id;
  }
  EXPECT_TRUE(sent_lss().empty());
}

TEST_F(LssTest, BitTimingStoreAndActivate) {
  add_node(1, 5);
  run([&](LssCallback cb) { lss.switch_global(LssMode::kConfiguration, cb); });
  EXPECT_TRUE(run([&](LssCallback cb) { lss.configure_bit_timing(4, cb); }).ok());
  EXPECT_EQ(nodes[0]->lss().pending_bit_timing(), 4);
  EXPECT_TRUE(run([&](LssCallback cb) { lss.configure_node_id(7, cb); }).ok());
  EXPECT_TRUE(run([&](LssCallback cb) { lss.store(cb); }).ok());
  EXPECT_EQ(nodes[0]->lss().stored_node_id(), 7);
  EXPECT_EQ(nodes[0]->lss().stored_bit_timing(), 4);
  EXPECT_TRUE(run([&](LssCallback cb) { lss.activate_bit_timing(100ms, cb); }).ok());
  EXPECT_EQ(nodes[0]->lss().activated_delay_ms(), 100);
  // Power cycle: the stored node-ID is the one it boots with.
  bus.clear_log();
  nodes[0]->power_on();
  bus.deliver();
  EXPECT_EQ(nodes[0]->drive()->config().node, 7);
  EXPECT_EQ(to_string(bus.log().back()), "707#00");
}

TEST_F(LssTest, SlaveErrorCodesAreReported) {
  auto& n = add_node(1, 5);
  run([&](LssCallback cb) { lss.switch_global(LssMode::kConfiguration, cb); });
  auto r = run([&](LssCallback cb) { lss.configure_bit_timing(9, cb); });
  EXPECT_EQ(r.error, LssError::kRefused);
  EXPECT_EQ(r.code, 1) << "automatic bit rate detection is not supported";
  r = run([&](LssCallback cb) { lss.configure_bit_timing(0, cb, 1); });
  EXPECT_EQ(r.error, LssError::kRefused) << "table selector 1";
  n.lss().faults().store_unsupported = true;
  r = run([&](LssCallback cb) { lss.store(cb); });
  EXPECT_EQ(r.error, LssError::kRefused);
  EXPECT_EQ(r.code, 1);
  EXPECT_EQ(describe(r), "refused by the slave (error code 1)");
  n.lss().faults() = {};
  n.lss().faults().store_fails = true;
  r = run([&](LssCallback cb) { lss.store(cb); });
  EXPECT_EQ(r.code, 2);
}

// A slave written by hand: answers configure node-ID with an out-of-range
// code and with the implementation-specific one.
TEST_F(LssTest, ConfigureNodeIdErrorCodesFromTheSlave) {
  std::uint8_t code = 1;
  std::size_t port = 0;
  port = bus.attach([&](const CanFrame& f) {
    if (f.id == cob::kLssMaster && f.data[0] == lss_cs::kConfigureNodeId)
      bus.sender(port)(make_frame(cob::kLssSlave, {0x11, code, 0x42, 0, 0, 0, 0, 0}));
  });
  auto r = run([&](LssCallback cb) { lss.configure_node_id(3, cb); });
  EXPECT_EQ(r.error, LssError::kRefused);
  EXPECT_EQ(r.code, 1);
  code = 0xFF;
  r = run([&](LssCallback cb) { lss.configure_node_id(3, cb); });
  EXPECT_EQ(r.code, 0xFF);
  EXPECT_EQ(r.specific, 0x42);
  EXPECT_EQ(describe(r), "refused by the slave (error code 0xFF, specific 0x42)");
}

TEST_F(LssTest, ASilentSlaveTimesOutAndTheNextServiceStillRuns) {
  auto& n = add_node(1, 5);
  n.lss().faults().silent = true;
  std::vector<LssResult> results;
  lss.switch_global(LssMode::kConfiguration, [&](const LssResult& r) { results.push_back(r); });
  lss.inquire(LssInquiry::kNodeId, [&](const LssResult& r) { results.push_back(r); });
  lss.store([&](const LssResult& r) { results.push_back(r); });
  const TimePoint start = clock.now();
  ASSERT_TRUE(run_until([&] { return results.size() == 3; }));
  EXPECT_TRUE(results[0].ok());
  EXPECT_EQ(results[1].error, LssError::kTimeout);
  EXPECT_EQ(results[2].error, LssError::kTimeout);
  EXPECT_EQ(clock.now() - start, 2 * kLssConfig.timeout);
  EXPECT_FALSE(lss.busy());
  n.lss().faults().silent = false;
  EXPECT_EQ(run([&](LssCallback cb) { lss.inquire(LssInquiry::kNodeId, cb); }).value, 5u);
}

// LSS answers carry no address: when two slaves are in configuration state
// both answer, and the master says so instead of taking the first.
TEST_F(LssTest, TwoSlavesAnsweringAnInquireIsAnError) {
  add_node(1, 5);
  add_node(2, 6);
  run([&](LssCallback cb) { lss.switch_global(LssMode::kConfiguration, cb); });
  const auto r = run([&](LssCallback cb) { lss.inquire(LssInquiry::kSerial, cb); });
  EXPECT_EQ(r.error, LssError::kMultipleAnswers);
  EXPECT_EQ(r.answers, 2u);
  EXPECT_EQ(describe(r), "more than one slave answered (2 answers)");
  EXPECT_EQ(lss.unexpected_answers(), 0u) << "the second answer came within the settle time";
}

TEST_F(LssTest, IdentifyNonConfiguredCountsTheSlavesWithoutNodeId) {
  add_node(1, kLssUnconfigured);
  add_node(2, 5);
  add_node(3, kLssUnconfigured);
  const auto r = run([&](LssCallback cb) { lss.identify_non_configured(cb); });
  EXPECT_TRUE(r.ok());
  EXPECT_EQ(r.answers, 2u);
}

TEST_F(LssTest, AnUnconfiguredNodeSaysNothingButLss) {
  auto& n = add_node(1, kLssUnconfigured);
  EXPECT_EQ(n.drive(), nullptr);
  EXPECT_TRUE(bus.log().empty()) << "no boot-up without node-ID";
  master.sdo(1).read<std::uint32_t>(0x1000, 0, [](std::error_code, std::uint32_t) {});
  std::optional<std::error_code> ec;
  master.sdo(1).read<std::uint32_t>(0x1000, 0, [&](std::error_code e, std::uint32_t) { ec = e; });
  run_until([&] { return ec.has_value(); });
  EXPECT_TRUE(ec && *ec);
}

TEST_F(LssTest, FastscanFindsTheSlaveAndLeavesItInConfigurationState) {
  add_node(0x0BADCAFE, kLssUnconfigured);
  std::optional<LssFastscanResult> found;
  lss.fastscan([&](const LssFastscanResult& r) { found = r; });
  ASSERT_TRUE(run_until([&] { return found.has_value(); }));
  EXPECT_TRUE(found->result.ok()) << describe(found->result);
  EXPECT_EQ(found->address, epos(0x0BADCAFE)) << to_string(found->address);
  EXPECT_EQ(nodes[0]->lss().mode(), LssMode::kConfiguration);
}

TEST_F(LssTest, FastscanWithKnownVendorAndProductScansOnlyTheRest) {
  add_node(77, kLssUnconfigured);
  std::optional<LssFastscanResult> found;
  lss.fastscan([&](const LssFastscanResult& r) { found = r; }, {0xFBu, 0x64200000u, std::nullopt, std::nullopt});
  ASSERT_TRUE(run_until([&] { return found.has_value(); }));
  EXPECT_TRUE(found->result.ok());
  EXPECT_EQ(found->address, epos(77));
  // reset + 2 confirms + 2 x (32 bits + confirm)
  EXPECT_EQ(sent_lss().size(), 1u + 2u + 2u * 33u);
  // A vendor-ID no slave has: nothing to find.
  found.reset();
  run([&](LssCallback cb) { lss.switch_global(LssMode::kWaiting, cb); });
  lss.fastscan([&](const LssFastscanResult& r) { found = r; }, {0x1234u, std::nullopt, std::nullopt, std::nullopt});
  ASSERT_TRUE(run_until([&] { return found.has_value(); }));
  EXPECT_EQ(found->result.error, LssError::kNotFound);
}

TEST_F(LssTest, FastscanWithoutNonConfiguredSlavesEndsAfterOneTimeout) {
  add_node(1, 5);
  const TimePoint start = clock.now();
  std::optional<LssFastscanResult> found;
  lss.fastscan([&](const LssFastscanResult& r) { found = r; });
  ASSERT_TRUE(run_until([&] { return found.has_value(); }));
  EXPECT_EQ(found->result.error, LssError::kNotFound);
  EXPECT_EQ(clock.now() - start, kLssConfig.timeout);
}

TEST_F(LssTest, FastscanReportsASlaveLostHalfWay) {
  auto& n = add_node(0xFFFFFFFF, kLssUnconfigured);
  std::optional<LssFastscanResult> found;
  lss.fastscan([&](const LssFastscanResult& r) { found = r; });
  // Gone after the reset step and a few bits of the vendor-ID.
  run_until([&] { return sent_lss().size() >= 4; });
  n.lss().faults().silent = true;
  ASSERT_TRUE(run_until([&] { return found.has_value(); }));
  EXPECT_EQ(found->result.error, LssError::kLost);
}

// The scenario of issue 23: three drives without node-ID on one bus; the
// scan finds each, gives it a node-ID, and each boots with it.
TEST_F(LssTest, ScanAssignsNodeIdsToThreeUnconfiguredNodesWhichThenBoot) {
  add_node(0x00000102, kLssUnconfigured);
  add_node(0x00000101, kLssUnconfigured);
  add_node(0x80000000, kLssUnconfigured);
  std::vector<HeartbeatUpdate> boots;
  auto hb = master.add_heartbeat_listener([&](const HeartbeatUpdate& u) {
    if (u.event == HeartbeatEvent::kBootUp) boots.push_back(u);
  });
  for (std::uint8_t n : {10, 11, 12}) master.heartbeat_consumer().monitor(n, Duration{});
  std::optional<std::vector<LssFound>> found;
  std::optional<LssResult> result;
  lss_scan(lss, 10, true, [&](const std::vector<LssFound>& f, const LssResult& r) {
    found = f;
    result = r;
  });
  ASSERT_TRUE(run_until([&] { return result.has_value(); }, 600s));
  EXPECT_TRUE(result->ok()) << describe(*result);
  ASSERT_EQ(found->size(), 3u);
  // The fastscan takes the lowest address first (a 0 wins each bit).
  EXPECT_EQ((*found)[0].address, epos(0x101));
  EXPECT_EQ((*found)[0].node_id, 10);
  EXPECT_EQ((*found)[1].address, epos(0x102));
  EXPECT_EQ((*found)[1].node_id, 11);
  EXPECT_EQ((*found)[2].address, epos(0x80000000));
  EXPECT_EQ((*found)[2].node_id, 12);
  // Each booted with its node-ID (boot-up message) and stored it.
  ASSERT_EQ(boots.size(), 3u);
  EXPECT_EQ(boots[0].node, 10);
  EXPECT_EQ(boots[1].node, 11);
  EXPECT_EQ(boots[2].node, 12);
  EXPECT_EQ(nodes[1]->drive()->config().node, 10);
  EXPECT_EQ(nodes[0]->drive()->config().node, 11);
  EXPECT_EQ(nodes[2]->drive()->config().node, 12);
  for (auto& n : nodes) {
    EXPECT_EQ(n->lss().mode(), LssMode::kWaiting);
    EXPECT_EQ(n->lss().stored_node_id(), n->lss().active_node_id());
  }
  // And they answer SDO there: the serial number of node 11.
  std::optional<std::uint32_t> serial;
  master.sdo(11).read<std::uint32_t>(0x1018, 4, [&](std::error_code ec, std::uint32_t v) {
    if (!ec) serial = v;
  });
  ASSERT_TRUE(run_until([&] { return serial.has_value(); }, 1s));
  EXPECT_EQ(*serial, 0x102u);
  // Nothing left to find.
  std::optional<LssFastscanResult> again;
  lss.fastscan([&](const LssFastscanResult& r) { again = r; });
  ASSERT_TRUE(run_until([&] { return again.has_value(); }));
  EXPECT_EQ(again->result.error, LssError::kNotFound);
}

TEST_F(LssTest, ScanWithoutAssignmentFindsAllAndChangesNothing) {
  add_node(3, kLssUnconfigured);
  add_node(1, kLssUnconfigured);
  add_node(2, 5);
  std::optional<std::vector<LssFound>> found;
  lss_scan(lss, std::nullopt, false, [&](const std::vector<LssFound>& f, const LssResult& r) {
    EXPECT_TRUE(r.ok()) << describe(r);
    found = f;
  });
  ASSERT_TRUE(run_until([&] { return found.has_value(); }, 600s));
  ASSERT_EQ(found->size(), 2u) << "the node with node-ID 5 takes no part";
  EXPECT_EQ((*found)[0].address, epos(1));
  EXPECT_EQ((*found)[1].address, epos(3));
  EXPECT_EQ((*found)[0].node_id, kLssUnconfigured);
  for (auto& n : nodes) EXPECT_EQ(n->lss().mode(), LssMode::kWaiting);
  EXPECT_EQ(nodes[0]->drive(), nullptr);
  EXPECT_EQ(nodes[1]->drive(), nullptr);
}

// An IclA (vendor 0x5A) without node-ID beside two EPOS: a scan for the
// EPOS vendor-ID numbers the EPOS only.
TEST_F(LssTest, ScanWithAKnownVendorFindsOnlyItsNodes) {
  add_node(7, kLssUnconfigured);
  DriveSimConfig icla;
  icla.profile = DriveProfile::kIcla;
  icla.serial = 1;  // the lowest address of the three
  add_node(icla, kLssUnconfigured);
  add_node(8, kLssUnconfigured);
  std::optional<std::vector<LssFound>> found;
  lss_scan(
      lss, 50, false,
      [&](const std::vector<LssFound>& f, const LssResult& r) {
        EXPECT_TRUE(r.ok()) << describe(r);
        found = f;
      },
      {0xFBu, std::nullopt, std::nullopt, std::nullopt});
  ASSERT_TRUE(run_until([&] { return found.has_value(); }, 600s));
  ASSERT_EQ(found->size(), 2u);
  EXPECT_EQ((*found)[0].address, epos(7));
  EXPECT_EQ((*found)[1].address, epos(8));
  EXPECT_EQ(nodes[1]->lss().active_node_id(), kLssUnconfigured) << "the IclA keeps no node-ID";
  EXPECT_EQ(nodes[0]->lss().active_node_id(), 50);
  EXPECT_EQ(nodes[2]->lss().active_node_id(), 51);
}

TEST_F(LssTest, ScanStopsAtTheFirstErrorWithEverySlaveBackInWaiting) {
  auto& n = add_node(1, kLssUnconfigured);
  n.lss().faults().store_fails = true;
  std::optional<LssResult> result;
  std::vector<LssFound> found;
  lss_scan(lss, 20, true, [&](const std::vector<LssFound>& f, const LssResult& r) {
    found = f;
    result = r;
  });
  ASSERT_TRUE(run_until([&] { return result.has_value(); }, 600s));
  EXPECT_EQ(result->error, LssError::kRefused);
  EXPECT_EQ(result->code, 2);
  ASSERT_EQ(found.size(), 1u);
  EXPECT_EQ(n.lss().mode(), LssMode::kWaiting);
  // Configured but not stored: it runs with node-ID 20 until power-off.
  ASSERT_NE(n.drive(), nullptr);
  EXPECT_EQ(n.drive()->config().node, 20);
  EXPECT_EQ(n.lss().stored_node_id(), kLssUnconfigured);
}

// A stray answer in the step for bit 0 of the vendor-ID (0xFB: a 1) makes
// the master take a 0 there; the word's confirm fails, and the scan starts
// the fastscan again, which finds the slave.
TEST_F(LssTest, ScanStartsAFastscanAgainWhenItLostItsSlave) {
  add_node(5, kLssUnconfigured);
  int strays = 1;
  std::size_t port = 0;
  port = bus.attach([&](const CanFrame& f) {
    if (f.id == cob::kLssMaster && f.data[0] == lss_cs::kFastscan && f.data[5] == 0 && f.data[6] == 0 &&
        f.data[7] == 0 && strays > 0) {
      --strays;
      bus.sender(port)(make_frame(cob::kLssSlave, {lss_cs::kIdentifySlave, 0, 0, 0, 0, 0, 0, 0}));
    }
  });
  std::optional<LssResult> result;
  std::vector<LssFound> found;
  lss_scan(lss, 40, false, [&](const std::vector<LssFound>& f, const LssResult& r) {
    found = f;
    result = r;
  });
  ASSERT_TRUE(run_until([&] { return result.has_value(); }, 600s));
  EXPECT_TRUE(result->ok()) << describe(*result);
  ASSERT_EQ(found.size(), 1u);
  EXPECT_EQ(found[0].address, epos(5));
  EXPECT_EQ(found[0].node_id, 40);
  EXPECT_EQ(strays, 0) << "the stray answer came";
}

// Without retries left, kLost is the scan's result.
TEST_F(LssTest, ScanGivesUpAfterTwoRetries) {
  add_node(5, kLssUnconfigured);
  std::size_t port = 0;
  port = bus.attach([&](const CanFrame& f) {
    if (f.id == cob::kLssMaster && f.data[0] == lss_cs::kFastscan && f.data[5] == 0 && f.data[6] == 0 &&
        f.data[7] == 0)
      bus.sender(port)(make_frame(cob::kLssSlave, {lss_cs::kIdentifySlave, 0, 0, 0, 0, 0, 0, 0}));
  });
  std::optional<LssResult> result;
  lss_scan(lss, 40, false, [&](const std::vector<LssFound>&, const LssResult& r) { result = r; });
  ASSERT_TRUE(run_until([&] { return result.has_value(); }, 600s));
  EXPECT_EQ(result->error, LssError::kLost);
  std::size_t resets = 0;
  for (const auto& s : sent_lss()) resets += s == "7E5#5100000000800000";
  EXPECT_EQ(resets, 3u);
}

TEST_F(LssTest, CancelAllEndsTheActiveAndQueuedServices) {
  std::vector<LssError> errors;
  lss.inquire(LssInquiry::kVendor, [&](const LssResult& r) { errors.push_back(r.error); });
  lss.fastscan([&](const LssFastscanResult& r) { errors.push_back(r.result.error); });
  lss.cancel_all();
  EXPECT_EQ(errors, (std::vector<LssError>{LssError::kCancelled, LssError::kCancelled}));
  EXPECT_FALSE(lss.busy());
  EXPECT_FALSE(lss.deadline().has_value());
}

TEST_F(LssTest, AnswersNobodyWaitsForAreCountedAndIgnored) {
  std::size_t port = bus.attach([](const CanFrame&) {});
  bus.sender(port)(make_frame(cob::kLssSlave, {0x5E, 3, 0, 0, 0, 0, 0, 0}));
  bus.deliver();
  EXPECT_EQ(lss.unexpected_answers(), 1u);
}

TEST_F(LssTest, DestroyedWhileBusyLeavesTheMasterClean) {
  auto bound = std::make_unique<LssMaster>(master, kLssConfig);
  bool called = false;
  bound->inquire(LssInquiry::kVendor, [&](const LssResult&) { called = true; });
  EXPECT_TRUE(master.next_deadline().has_value());
  bound.reset();
  // Its subscription and its poll registration went with it.
  std::size_t port = bus.attach([](const CanFrame&) {});
  bus.sender(port)(make_frame(cob::kLssSlave, {0x5A, 0, 0, 0, 0, 0, 0, 0}));
  bus.deliver();
  clock.advance(1s);
  master.poll();
  EXPECT_FALSE(called);
}

}  // namespace
}  // namespace advee::canopen
