// SPDX-License-Identifier: GPL-2.0
// The drive drivers with a device description (DriveConfig::device): the
// EPOS driver boots the simulated EPOS after the CiA 302-2 identity check and
// the DCF download, and refuses a drive whose identity differs, with both
// values in its boot error and no write and no NMT command to it.
#include <gtest/gtest.h>

#include "advee/canopen/drivers/epos.hpp"
#include "advee/canopen/node_boot.hpp"
#include "advee/canopen/sim/drive_sim.hpp"
#include "advee/canopen/virtual_bus.hpp"

namespace advee::canopen::drivers {
namespace {

using namespace std::chrono_literals;

class DriveDeviceTest : public testing::Test {
 protected:
  ManualClock clock;
  VirtualBus bus;
  std::size_t mport = bus.attach([this](const CanFrame& f) { master.handle(f); });
  std::size_t eport = bus.attach([this](const CanFrame& f) { epos_sim.handle(f); });
  Master master{MasterConfig{0x7F, 200ms, 100ms}, bus.sender(mport), clock.fn()};
  sim::SimulatedDrive epos_sim{sim::DriveSimConfig{1, sim::DriveProfile::kEpos}, bus.sender(eport), clock.fn()};

  void SetUp() override {
    epos_sim.power_on();
    bus.deliver();
    bus.clear_log();
  }
  void tick() {
    clock.advance(1ms);
    master.poll();
    epos_sim.poll();
    bus.deliver();
  }
  std::error_code wait(const std::function<void(Drive402::Done)>& op) {
    std::optional<std::error_code> r;
    op([&r](std::error_code ec) { r = ec; });
    for (int i = 0; i < 60000 && !r; ++i) tick();
    EXPECT_TRUE(r) << "operation did not complete";
    return r.value_or(make_error_code(AxisError::kTransitionTimeout));
  }
  static NodeBootConfig shipped_epos() {
    DescriptionResult r = parse_device_description(sim::shipped_eds(sim::DriveProfile::kEpos), "epos-70-10.eds", 1);
    EXPECT_TRUE(r.description);
    return boot_config_from_dcf(*r.description, "epos");
  }
};

TEST_F(DriveDeviceTest, EposWithItsEdsBootsAndDrives) {
  EposConfig c;
  c.drive.device = shipped_epos();
  EposDriver epos(master, c);
  ASSERT_FALSE(wait([&](auto d) { epos.boot(d); })) << epos.drive().boot_error();
  ASSERT_FALSE(wait([&](auto d) { epos.enable(d); }));
  ASSERT_TRUE(epos.set_speed(0.5));
  for (int i = 0; i < 500; ++i) tick();
  ASSERT_TRUE(epos.speed());
  EXPECT_NEAR(*epos.speed(), 0.5, 0.001);
}

TEST_F(DriveDeviceTest, EposRefusesAnotherProduct) {
  EposConfig c;
  c.drive.device = shipped_epos();
  c.drive.device->identity[1] = 0x64200001;
  EposDriver epos(master, c);
  const std::error_code ec = wait([&](auto d) { epos.boot(d); });
  EXPECT_EQ(ec, make_error_code(BootError::kWrongDevice));
  EXPECT_NE(epos.drive().boot_error().find("epos (node 1): boot failed: wrong device: 0x1018:2 product code "
                                           "expected 0x64200001, found 0x64200000"),
            std::string::npos)
      << epos.drive().boot_error();
  for (const CanFrame& f : bus.log()) {
    EXPECT_FALSE(f.id == 0x601 && (f.data[0] & 0xE0) == 0x20) << "SDO download to the refused node";
    EXPECT_FALSE(f.id == 0 && (f.data[1] == 1 || f.data[1] == 0)) << "NMT command to the refused node";
  }
  EXPECT_EQ(epos_sim.nmt_state(), NmtState::kPreOperational);
}

// The DCF moves the velocity feedback to TPDO3 (6041 + 606C, valid): the
// driver takes that layout from the DCF instead of its built-in TPDO4.
TEST_F(DriveDeviceTest, EposTakesItsPdoLayoutFromTheDcf) {
  std::string dcf(sim::shipped_eds(sim::DriveProfile::kEpos));
  auto param = [&dcf](const std::string& section, const std::string& value) {
    const auto at = dcf.find("[" + section + "]\n");
    ASSERT_NE(at, std::string::npos) << section;
    dcf.insert(dcf.find("\n\n", at) + 1, "ParameterValue=" + value + "\n");
  };
  param("1802sub1", "$NODEID+0x40000380");
  param("1A02sub2", "0x606C0020");
  DescriptionResult r = parse_device_description(dcf + "\n[DeviceComissioning]\nNodeID=1\n", "epos.dcf");
  ASSERT_TRUE(r.description);
  EposConfig c;
  c.drive.device = boot_config_from_dcf(*r.description, "epos");
  EposDriver epos(master, c);
  EXPECT_EQ(epos.drive().config().status_tpdo, 3u);
  EXPECT_EQ(epos.drive().config().control_rpdo, 4u);  // the DCF's RPDO4 default, as before
  ASSERT_FALSE(wait([&](auto d) { epos.boot(d); })) << epos.drive().boot_error();
  EXPECT_EQ(epos.drive().status_mapping().number, 3u);
  EXPECT_EQ(epos.drive().status_mapping().can_id(), 0x381u);
  ASSERT_FALSE(wait([&](auto d) { epos.enable(d); }));
  ASSERT_TRUE(epos.set_speed(0.5));
  for (int i = 0; i < 500; ++i) tick();
  ASSERT_TRUE(epos.speed());
  EXPECT_NEAR(*epos.speed(), 0.5, 0.001);
  EXPECT_EQ(epos_sim.od().get<std::uint32_t>(0x1803, 1) & kPdoCobInvalid, kPdoCobInvalid);  // TPDO4 left off
}

}  // namespace
}  // namespace advee::canopen::drivers
