// SPDX-License-Identifier: GPL-2.0
// EPOS and IclA drivers against the simulated drives: units, boot, homing,
// steering moves.
#include <gtest/gtest.h>

#include <numbers>

#include "advee/canopen/drivers/epos.hpp"
#include "advee/canopen/drivers/icla.hpp"
#include "advee/canopen/sim/drive_sim.hpp"
#include "advee/canopen/virtual_bus.hpp"

namespace advee::canopen::drivers {
namespace {

using namespace std::chrono_literals;

class DriversTest : public testing::Test {
 protected:
  ManualClock clock;
  VirtualBus bus;
  std::size_t mport = bus.attach([this](const CanFrame& f) { master.handle(f); });
  std::size_t eport = bus.attach([this](const CanFrame& f) { epos_sim.handle(f); });
  std::size_t iport = bus.attach([this](const CanFrame& f) { icla_sim.handle(f); });
  Master master{MasterConfig{0x7F, 200ms, 100ms}, bus.sender(mport), clock.fn()};
  sim::SimulatedDrive epos_sim{sim::DriveSimConfig{1, sim::DriveProfile::kEpos}, bus.sender(eport), clock.fn()};
  sim::SimulatedDrive icla_sim{sim::DriveSimConfig{2, sim::DriveProfile::kIcla, 1.0, -800}, bus.sender(iport),
                               clock.fn()};

  void SetUp() override {
    epos_sim.power_on();
    icla_sim.power_on();
    bus.deliver();
  }
  void tick() {
    clock.advance(1ms);
    master.poll();
    epos_sim.poll();
    icla_sim.poll();
    bus.deliver();
  }
  std::error_code wait(const std::function<void(Drive402::Done)>& op) {
    std::optional<std::error_code> r;
    op([&r](std::error_code ec) { r = ec; });
    for (int i = 0; i < 60000 && !r; ++i) tick();
    EXPECT_TRUE(r) << "operation did not complete";
    return r.value_or(make_error_code(AxisError::kTransitionTimeout));
  }
};

TEST(EposUnitsTest, WheelSpeedToMotorRpmWithGearRatio) {
  ManualClock clock;
  Master m{MasterConfig{}, [](const CanFrame&) {}, clock.fn()};
  EposConfig c;
  c.gear_ratio = 26;
  c.wheel_radius_m = 0.1;
  EposDriver epos(m, c);
  // 1 m/s on a 0.1 m wheel = 1.5915 wheel rev/s = 95.49 rpm at the wheel, x26 at the motor.
  EXPECT_EQ(epos.rpm_for(1.0), 2483);
  EXPECT_EQ(epos.rpm_for(-0.5), -1241);
  EXPECT_NEAR(epos.m_per_s_for(2483), 1.0, 1e-3);
}

TEST_F(DriversTest, EposBootsIntoProfileVelocityAndFollowsSpeedCommands) {
  EposDriver epos(master, EposConfig{});
  ASSERT_FALSE(wait([&](auto d) { epos.boot(d); }));
  EXPECT_EQ(epos_sim.od().get<std::int8_t>(0x6061), 3);
  EXPECT_EQ(epos_sim.od().get<std::uint32_t>(0x6085), 20000u);
  ASSERT_FALSE(wait([&](auto d) { epos.enable(d); }));
  ASSERT_TRUE(epos.set_speed(0.8));
  for (int i = 0; i < 500; ++i) tick();
  ASSERT_TRUE(epos.speed());
  EXPECT_NEAR(*epos.speed(), 0.8, 0.001);
  EXPECT_EQ(epos_sim.od().get<std::int32_t>(0x60FF), epos.rpm_for(0.8));
}

TEST_F(DriversTest, IclaHomesOnTheSwitchThenSteers) {
  IclaConfig c;
  c.units_per_rad = 1000;
  c.home_offset = 100;
  c.homing_speed = 4000;
  IclaDriver icla(master, c);
  ASSERT_FALSE(wait([&](auto d) { icla.boot(d); }));
  ASSERT_FALSE(wait([&](auto d) { icla.enable(d); }));
  ASSERT_FALSE(wait([&](auto d) { icla.home(d); }));
  EXPECT_EQ(icla_sim.od().get<std::int8_t>(0x6098), 19);
  EXPECT_EQ(icla_sim.od().get<std::int8_t>(0x6061), 1) << "back in profile position after homing";
  ASSERT_TRUE(icla.angle());
  EXPECT_DOUBLE_EQ(*icla.angle(), 0.1);
  ASSERT_FALSE(wait([&](auto d) { icla.set_angle(-0.35, d); }));
  EXPECT_DOUBLE_EQ(*icla.angle(), -0.35);
}

}  // namespace
}  // namespace advee::canopen::drivers
