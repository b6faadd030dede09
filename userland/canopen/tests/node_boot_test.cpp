// SPDX-License-Identifier: GPL-2.0
// The CiA 302-2 style boot of one node (NodeBoot) against the simulated
// drives, configured from a DCF made of the shipped EDS: identity checked
// before anything is written, a wrong device refused with both values and
// untouched, the DCF's PDO remap downloaded in an order the device takes,
// timeouts retried, an abort ends the boot, NMT start last.
#include <gtest/gtest.h>

#include <cstdio>
#include <fstream>

#include "advee/canopen/node_boot.hpp"
#include "advee/canopen/pdo.hpp"
#include "advee/canopen/sim/drive_sim.hpp"
#include "advee/canopen/virtual_bus.hpp"

namespace advee::canopen {
namespace {

using namespace std::chrono_literals;

// The shipped EPOS EDS as a DCF for node 1: heartbeat 100 ms, and TPDO2
// remapped to statusword + position actual value and enabled.
std::string epos_dcf() {
  std::string t(sim::shipped_eds(sim::DriveProfile::kEpos));
  auto param = [&t](const std::string& section, const std::string& value) {
    const auto at = t.find("[" + section + "]\n");
    EXPECT_NE(at, std::string::npos) << section;
    t.insert(t.find("\n\n", at) + 1, "ParameterValue=" + value + "\n");
  };
  param("1017", "100");
  param("1801sub1", "$NODEID+0x40000280");
  param("1A01sub2", "0x60640020");
  param("1A01sub0", "2");
  return t + "\n[DeviceComissioning]\nNodeID=1\nNodeName=epos\n";
}

DeviceDescription parse(const std::string& text) {
  DescriptionResult r = parse_device_description(text, "epos.dcf");
  for (const auto& e : r.errors) ADD_FAILURE() << e.text();
  return r.description ? std::move(*r.description) : DeviceDescription{};
}

TEST(NodeBootConfigTest, IdentityAndPdoOrderFromTheDcf) {
  const NodeBootConfig c = boot_config_from_dcf(parse(epos_dcf()), "epos");
  EXPECT_EQ(c.node, 1);
  EXPECT_EQ(c.device_type, 0x00020192u);
  EXPECT_EQ(c.identity[0], 0x000000FBu);
  EXPECT_EQ(c.identity[1], 0x64200000u);
  EXPECT_EQ(c.identity[2], 0x00010000u);
  EXPECT_FALSE(c.identity[3]);  // the EDS's serial ($NODEID) is no ParameterValue
  const std::vector<SdoWrite> want = {
      SdoWrite::of<std::uint16_t>(0x1017, 0, 100),
      SdoWrite::of<std::uint32_t>(0x1801, 1, 0xC0000281),  // invalid first
      SdoWrite::of<std::uint8_t>(0x1A01, 0, 0),             // mapping off
      SdoWrite::of<std::uint32_t>(0x1A01, 2, 0x60640020),
      SdoWrite::of<std::uint8_t>(0x1A01, 0, 2),             // mapping on
      SdoWrite::of<std::uint32_t>(0x1801, 1, 0x40000281),  // valid last
  };
  EXPECT_EQ(c.configuration, want);
}

class NodeBootTest : public testing::Test {
 protected:
  ManualClock clock;
  VirtualBus bus;
  std::size_t mport = bus.attach([this](const CanFrame& f) { master.handle(f); });
  std::size_t dport = bus.attach([this](const CanFrame& f) {
    if (drive) drive->handle(f);
  });
  Master master{MasterConfig{0x7F, 200ms}, bus.sender(mport), clock.fn()};
  std::unique_ptr<sim::SimulatedDrive> drive;
  std::string eds_path;

  void start_drive(const std::string& eds = {}) {
    sim::DriveSimConfig c;
    c.node = 1;
    if (!eds.empty()) {
      eds_path = testing::TempDir() + "node-boot-drive.eds";
      std::ofstream(eds_path) << eds;
      c.eds_file = eds_path;
    }
    drive = std::make_unique<sim::SimulatedDrive>(c, bus.sender(dport), clock.fn());
    drive->power_on();
    bus.deliver();
    bus.clear_log();
  }
  void TearDown() override {
    if (!eds_path.empty()) std::remove(eds_path.c_str());
  }
  void tick() {
    clock.advance(1ms);
    master.poll();
    drive->poll();
    bus.deliver();
  }
  struct Outcome {
    std::error_code ec;
    std::string error;
  };
  Outcome run(NodeBoot& boot) {
    std::optional<Outcome> r;
    boot.boot([&r](std::error_code ec, const std::string& e) { r = Outcome{ec, e}; });
    bus.deliver();
    for (int i = 0; i < 5000 && !r; ++i) tick();
    EXPECT_TRUE(r) << "boot did not end";
    return r.value_or(Outcome{});
  }
  // Master -> node frames of one kind.
  std::size_t sdo_downloads_to(std::uint8_t node, std::uint16_t first, std::uint16_t last) const {
    std::size_t n = 0;
    for (const CanFrame& f : bus.log())
      if (f.id == 0x600u + node && f.len == 8 && (f.data[0] & 0xE0) == 0x20) {
        const auto index = static_cast<std::uint16_t>(f.data[1] | (f.data[2] << 8));
        if (index >= first && index <= last) ++n;
      }
    return n;
  }
  std::size_t nmt_to(std::uint8_t node) const {
    std::size_t n = 0;
    for (const CanFrame& f : bus.log())
      if (f.id == 0 && f.len == 2 && (f.data[1] == node || f.data[1] == 0)) ++n;
    return n;
  }
};

TEST_F(NodeBootTest, RightDeviceIsConfiguredFromItsDcfAndStarted) {
  start_drive();
  NodeBoot boot(master, boot_config_from_dcf(parse(epos_dcf()), "epos"));
  const Outcome o = run(boot);
  EXPECT_FALSE(o.ec) << o.error;
  EXPECT_TRUE(boot.booted());
  EXPECT_EQ(drive->nmt_state(), NmtState::kOperational);
  EXPECT_EQ(drive->od().get<std::uint16_t>(0x1017), 100);
  EXPECT_EQ(drive->od().get<std::uint32_t>(0x1801, 1), 0x40000281u);
  EXPECT_EQ(drive->od().get<std::uint8_t>(0x1A01, 0), 2);
  EXPECT_EQ(drive->od().get<std::uint32_t>(0x1A01, 2), 0x60640020u);
  // Identity read before the first write, the start after the last.
  std::size_t first_write = 0, last_read = 0, start = 0;
  for (std::size_t i = 0; i < bus.log().size(); ++i) {
    const CanFrame& f = bus.log()[i];
    if (f.id == 0x601 && (f.data[0] & 0xE0) == 0x40) last_read = i;
    if (f.id == 0x601 && (f.data[0] & 0xE0) == 0x20 && !first_write) first_write = i;
    if (f.id == 0 && f.data[0] == static_cast<std::uint8_t>(NmtCommand::kStart)) start = i;
  }
  EXPECT_LT(last_read, first_write);
  EXPECT_GT(start, first_write);
  EXPECT_EQ(boot.retries(), 0u);
}

// The node at node-ID 1 reports another product code in its EDS than the
// DCF expects: refused with both values, not written to, not started.
TEST_F(NodeBootTest, WrongIdentityIsRefusedWithBothValuesAndTheNodeIsNotTouched) {
  std::string eds(sim::shipped_eds(sim::DriveProfile::kEpos));
  eds.replace(eds.find("DefaultValue=0x64200000"), 23, "DefaultValue=0x64200001");
  start_drive(eds);
  NodeBoot boot(master, boot_config_from_dcf(parse(epos_dcf()), "epos"));
  const Outcome o = run(boot);
  EXPECT_EQ(o.ec, make_error_code(BootError::kWrongDevice));
  EXPECT_EQ(o.error, boot.error());
  EXPECT_NE(o.error.find("epos (node 1): boot failed: wrong device: 0x1018:2 product code expected 0x64200000, "
                         "found 0x64200001"),
            std::string::npos)
      << o.error;
  EXPECT_FALSE(boot.booted());
  EXPECT_EQ(sdo_downloads_to(1, 0x0000, 0xFFFF), 0u);
  EXPECT_EQ(sdo_downloads_to(1, 0x1400, 0x1BFF), 0u);
  EXPECT_EQ(nmt_to(1), 0u);
  EXPECT_EQ(drive->nmt_state(), NmtState::kPreOperational);
  EXPECT_EQ(drive->od().get<std::uint32_t>(0x1801, 1), 0xC0000281u);  // the EDS default, untouched
  EXPECT_EQ(drive->od().get<std::uint16_t>(0x1017), 0);
}

TEST_F(NodeBootTest, EveryMismatchIsListedAndTheSerialIsCheckedWhereConfigured) {
  start_drive();
  NodeBootConfig c = boot_config_from_dcf(parse(epos_dcf()), "epos");
  c.device_type = 0x00020191;
  c.identity[3] = 7;  // the simulator's serial is its node-ID, 1
  NodeBoot boot(master, c);
  const Outcome o = run(boot);
  EXPECT_NE(o.error.find("0x1000:0 device type expected 0x00020191, found 0x00020192; "
                         "0x1018:4 serial number expected 0x00000007, found 0x00000001"),
            std::string::npos)
      << o.error;
  EXPECT_EQ(nmt_to(1), 0u);
}

TEST_F(NodeBootTest, TimeoutsAreRetried) {
  start_drive();
  NodeBoot boot(master, boot_config_from_dcf(parse(epos_dcf()), "epos"));
  // The drive's answers are lost for 250 ms: the first read times out twice
  // (200 ms each), the third attempt gets through.
  bus.mute(dport, true);
  std::optional<Outcome> r;
  boot.boot([&r](std::error_code ec, const std::string& e) { r = Outcome{ec, e}; });
  for (int i = 0; i < 250; ++i) tick();
  bus.mute(dport, false);
  for (int i = 0; i < 5000 && !r; ++i) tick();
  ASSERT_TRUE(r);
  EXPECT_FALSE(r->ec) << r->error;
  EXPECT_EQ(boot.retries(), 2u);
  EXPECT_EQ(drive->nmt_state(), NmtState::kOperational);
}

TEST_F(NodeBootTest, TimeoutOnEveryAttemptFailsTheBoot) {
  start_drive();
  NodeBootConfig c = boot_config_from_dcf(parse(epos_dcf()), "epos");
  c.sdo_attempts = 2;
  NodeBoot boot(master, c);
  bus.mute(dport, true);
  const Outcome o = run(boot);
  EXPECT_EQ(o.ec, make_error_code(SdoAbort::kTimeout));
  EXPECT_NE(o.error.find("reading device type 0x1000:0"), std::string::npos) << o.error;
  EXPECT_EQ(boot.retries(), 1u);
  EXPECT_EQ(nmt_to(1), 0u);
}

TEST_F(NodeBootTest, AnAbortEndsTheBootWithoutStart) {
  start_drive();
  drive->sdo().faults().abort_on[{0x1A01, 2}] = SdoAbort::kNotMappable;
  NodeBoot boot(master, boot_config_from_dcf(parse(epos_dcf()), "epos"));
  const Outcome o = run(boot);
  EXPECT_EQ(o.ec, make_error_code(SdoAbort::kNotMappable));
  EXPECT_NE(o.error.find("configuration 0x1A01:2 = 0x60640020 (write 4 of 6)"), std::string::npos) << o.error;
  EXPECT_EQ(boot.retries(), 0u);  // an abort is not retried
  EXPECT_EQ(drive->nmt_state(), NmtState::kPreOperational);
  for (const CanFrame& f : bus.log()) EXPECT_FALSE(f.id == 0 && f.data[0] == static_cast<std::uint8_t>(NmtCommand::kStart));
}

TEST_F(NodeBootTest, DestroyedDuringBootLeavesNoCallbackBehind) {
  start_drive();
  auto boot = std::make_unique<NodeBoot>(master, boot_config_from_dcf(parse(epos_dcf()), "epos"));
  bool called = false;
  boot->boot([&called](std::error_code, const std::string&) { called = true; });
  boot.reset();  // the first read is on the bus, its answer still to come
  for (int i = 0; i < 1000; ++i) tick();
  EXPECT_FALSE(called);
}

}  // namespace
}  // namespace advee::canopen
