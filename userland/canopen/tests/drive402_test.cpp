// SPDX-License-Identifier: GPL-2.0
// The master's drive driver against simulated drives in one process: boot
// with PDO read-back, enable, profile velocity, profile position, homing,
// mode change with halt, heartbeat both ways, EMCY, motion watchdog.
#include "advee/canopen/drive402.hpp"

#include <gtest/gtest.h>

#include "advee/canopen/motion_watchdog.hpp"
#include "advee/canopen/sim/drive_sim.hpp"
#include "advee/canopen/virtual_bus.hpp"

namespace advee::canopen {
namespace {

using namespace std::chrono_literals;
using cia402::Mode;
using cia402::State;

DriveConfig epos_config() {
  DriveConfig c;
  c.node = 1;
  c.name = "epos";
  c.control_rpdo = 4;
  c.control_entries = {PdoEntry::from_raw(0x60400010), PdoEntry::from_raw(0x60FF0020)};
  c.status_tpdo = 4;
  c.status_entries = {PdoEntry::from_raw(0x60410010), PdoEntry::from_raw(0x606C0020)};
  return c;
}

DriveConfig icla_config() {
  DriveConfig c;
  c.node = 2;
  c.name = "icla";
  c.control_rpdo = 2;
  c.control_entries = {PdoEntry::from_raw(0x60400010), PdoEntry::from_raw(0x607A0020)};
  c.status_tpdo = 2;
  c.status_entries = {PdoEntry::from_raw(0x60410010), PdoEntry::from_raw(0x60640020)};
  return c;
}

class DriveTest : public testing::Test {
 protected:
  ManualClock clock;
  VirtualBus bus;
  std::size_t mport = bus.attach([this](const CanFrame& f) { master.handle(f); });
  std::size_t eport = bus.attach([this](const CanFrame& f) { epos_sim.handle(f); });
  std::size_t iport = bus.attach([this](const CanFrame& f) { icla_sim.handle(f); });
  Master master{MasterConfig{0x7F, 200ms, 100ms}, bus.sender(mport), clock.fn()};
  sim::SimulatedDrive epos_sim{sim::DriveSimConfig{1, sim::DriveProfile::kEpos}, bus.sender(eport), clock.fn()};
  sim::SimulatedDrive icla_sim{sim::DriveSimConfig{2, sim::DriveProfile::kIcla, 1.0, -3000}, bus.sender(iport),
                               clock.fn()};
  std::vector<DriveEvent> events;

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
  void run_for(Duration d) {
    for (auto end = clock.now() + d; clock.now() < end;) tick();
  }
  // Runs until the operation calls back (or 60 s of simulated time).
  std::error_code wait(const std::function<void(Drive402::Done)>& op) {
    std::optional<std::error_code> r;
    op([&r](std::error_code ec) { r = ec; });
    for (int i = 0; i < 60000 && !r; ++i) tick();
    EXPECT_TRUE(r) << "operation did not complete";
    return r.value_or(make_error_code(AxisError::kTransitionTimeout));
  }
  std::unique_ptr<Drive402> make(DriveConfig c) {
    auto d = std::make_unique<Drive402>(master, c);
    d->on_event([this](const DriveEvent& e) { events.push_back(e); });
    return d;
  }
  static bool is_sdo(const CanFrame& f) { return (f.id & 0x780) == 0x580 || (f.id & 0x780) == 0x600; }
};

TEST_F(DriveTest, EposBootEnablesTxPdo4AndRunsProfileVelocityOnPdosOnly) {
  auto epos = make(epos_config());
  ASSERT_FALSE(wait([&](auto d) { epos->boot(d); }));
  EXPECT_EQ(epos_sim.nmt_state(), NmtState::kOperational);
  EXPECT_TRUE(epos->status_mapping().enabled());
  EXPECT_EQ(epos_sim.od().get<std::uint32_t>(0x1803, 1) & 0x80000000u, 0u) << "TxPDO4 switched on";
  EXPECT_EQ(epos_sim.od().get<std::uint16_t>(0x1017), 100);
  EXPECT_EQ(epos_sim.od().get<std::uint32_t>(0x1016, 1), 0x007F01F4u) << "drive consumes the master heartbeat";

  ASSERT_FALSE(wait([&](auto d) { epos->set_mode(Mode::kProfileVelocity, d); }));
  ASSERT_FALSE(wait([&](auto d) { epos->enable(d); }));
  EXPECT_EQ(epos_sim.state(), State::kOperationEnabled);

  bus.clear_log();
  ASSERT_TRUE(epos->set_target(0x60FF, 0, 1000));
  run_for(300ms);
  EXPECT_NEAR(epos_sim.velocity(), 1000, 0.5);
  EXPECT_EQ(epos->feedback(0x606C), 1000);
  ASSERT_TRUE(epos->set_target(0x60FF, 0, -500));
  run_for(300ms);
  EXPECT_EQ(epos->feedback(0x606C), -500);
  for (const CanFrame& f : bus.log()) EXPECT_FALSE(is_sdo(f)) << "SDO in the control loop: " << to_string(f);
  EXPECT_EQ(to_string(bus.log().front()), "501#0F00E8030000") << "RPDO4: controlword + target velocity";
}

TEST_F(DriveTest, BootFailsClearlyWhenTheMappingIsNotWhatTheDriverNeeds) {
  DriveConfig c = epos_config();
  c.control_rpdo = 2;  // EPOS RPDO2 maps 6040 + 6060, not the target velocity
  auto epos = make(c);
  EXPECT_EQ(wait([&](auto d) { epos->boot(d); }), make_error_code(AxisError::kPdoMismatch));
  EXPECT_FALSE(epos->booted());
  EXPECT_EQ(epos->boot_error(),
            "epos (node 1): boot failed: control RPDO: device PDO mapping is not what the driver needs "
            "(device has RPDO2 0x301 type 255: 6040:00/16 6060:00/8, driver needs 6040:00/16 60FF:00/32)");
  EXPECT_EQ(epos_sim.nmt_state(), NmtState::kPreOperational) << "not started with a wrong mapping";
}

TEST_F(DriveTest, BootRemapsWhenAllowed) {
  DriveConfig c = epos_config();
  c.control_rpdo = 2;
  c.remap_if_different = true;
  auto epos = make(c);
  ASSERT_FALSE(wait([&](auto d) { epos->boot(d); }));
  EXPECT_EQ(epos_sim.od().get<std::uint8_t>(0x1601, 0), 2);
  EXPECT_EQ(epos_sim.od().get<std::uint32_t>(0x1601, 2), 0x60FF0020u);
  ASSERT_FALSE(wait([&](auto d) { epos->set_mode(Mode::kProfileVelocity, d); }));
  ASSERT_FALSE(wait([&](auto d) { epos->enable(d); }));
  epos->set_target(0x60FF, 0, 200);
  run_for(200ms);
  EXPECT_NEAR(epos_sim.velocity(), 200, 0.5);
}

TEST_F(DriveTest, IclaProfilePositionWithSetPointHandshake) {
  auto icla = make(icla_config());
  ASSERT_FALSE(wait([&](auto d) { icla->boot(d); }));
  ASSERT_FALSE(wait([&](auto d) { icla->set_mode(Mode::kProfilePosition, d); }));
  ASSERT_FALSE(wait([&](auto d) { icla->enable(d); }));
  EXPECT_FALSE(wait([&](auto d) { icla->move_to(5000, false, d); }));
  EXPECT_EQ(icla->feedback(0x6064), 5000);
  EXPECT_EQ(icla->axis().controlword() & cia402::cw::kNewSetPoint, 0) << "bit 4 dropped after the acknowledge";
  EXPECT_FALSE(wait([&](auto d) { icla->move_to(-1500, true, d); }));
  EXPECT_EQ(icla->feedback(0x6064), 3500);
}

TEST_F(DriveTest, MoveIsRefusedOutsideProfilePosition) {
  auto icla = make(icla_config());
  ASSERT_FALSE(wait([&](auto d) { icla->boot(d); }));
  EXPECT_EQ(wait([&](auto d) { icla->move_to(1, false, d); }), make_error_code(AxisError::kNotReady));
}

TEST_F(DriveTest, IclaHomingOnTheSwitchSetsTheHomeOffset) {
  auto icla = make(icla_config());
  ASSERT_FALSE(wait([&](auto d) { icla->boot(d); }));
  icla_sim.od().set<std::int8_t>(0x6098, 0, 19);
  icla_sim.od().set<std::int32_t>(0x607C, 0, 250);
  icla_sim.od().set<std::uint32_t>(0x6099, 1, 2000);
  ASSERT_FALSE(wait([&](auto d) { icla->set_mode(Mode::kHoming, d); }));
  ASSERT_FALSE(wait([&](auto d) { icla->enable(d); }));
  EXPECT_FALSE(wait([&](auto d) { icla->home(d); }));
  EXPECT_EQ(icla->feedback(0x6064), 250);
}

TEST_F(DriveTest, HomingErrorIsReported) {
  auto icla = make(icla_config());
  ASSERT_FALSE(wait([&](auto d) { icla->boot(d); }));
  icla_sim.od().set<std::int8_t>(0x6098, 0, 19);
  icla_sim.od().set<std::uint32_t>(0x6099, 1, 20000);
  icla_sim.faults().homing_switch_missing = true;
  ASSERT_FALSE(wait([&](auto d) { icla->set_mode(Mode::kHoming, d); }));
  ASSERT_FALSE(wait([&](auto d) { icla->enable(d); }));
  EXPECT_EQ(wait([&](auto d) { icla->home(d); }), make_error_code(AxisError::kHomingError));
}

TEST_F(DriveTest, ModeChangeClearsHaltFirstForDrivesThatRefuseOtherwise) {
  icla_sim.faults().refuse_mode_change_while_halt = true;
  auto icla = make(icla_config());
  ASSERT_FALSE(wait([&](auto d) { icla->boot(d); }));
  ASSERT_FALSE(wait([&](auto d) { icla->enable(d); }));
  icla->halt(true);
  run_for(10ms);
  EXPECT_FALSE(wait([&](auto d) { icla->set_mode(Mode::kProfilePosition, d); }));
  EXPECT_EQ(icla_sim.od().get<std::int8_t>(0x6061), 1);
}

TEST_F(DriveTest, ModeDisplayThatNeverFollowsTimesOut) {
  auto icla = make(icla_config());
  ASSERT_FALSE(wait([&](auto d) { icla->boot(d); }));
  icla_sim.faults().ignore_mode_change = true;
  const TimePoint start = clock.now();
  EXPECT_EQ(wait([&](auto d) { icla->set_mode(Mode::kProfilePosition, d); }), make_error_code(AxisError::kModeTimeout));
  EXPECT_GE(clock.now() - start, 1s) << "the configured mode timeout";
  EXPECT_LT(clock.now() - start, 1100ms);
}

TEST_F(DriveTest, DriveHeartbeatLossAndEmcyAreReported) {
  auto epos = make(epos_config());
  ASSERT_FALSE(wait([&](auto d) { epos->boot(d); }));
  run_for(500ms);
  EXPECT_TRUE(events.empty());
  epos_sim.faults().heartbeat_silent = true;
  run_for(400ms);
  ASSERT_FALSE(events.empty());
  EXPECT_EQ(events.back().kind, DriveEventKind::kHeartbeatLost);
  epos_sim.faults().heartbeat_silent = false;
  run_for(200ms);
  EXPECT_EQ(events.back().kind, DriveEventKind::kHeartbeatResumed);

  events.clear();
  epos_sim.inject_fault(0x4210);
  run_for(10ms);
  ASSERT_EQ(events.size(), 2u);
  EXPECT_EQ(events[0].kind, DriveEventKind::kEmcy);
  EXPECT_EQ(events[0].emcy_code, 0x4210);
  EXPECT_EQ(events[1].kind, DriveEventKind::kFault);
  // Enabling again resets the fault.
  EXPECT_FALSE(wait([&](auto d) { epos->enable(d); }));
}

TEST_F(DriveTest, DeadMasterHeartbeatMakesTheDriveQuickStop) {
  auto epos = make(epos_config());
  ASSERT_FALSE(wait([&](auto d) { epos->boot(d); }));
  ASSERT_FALSE(wait([&](auto d) { epos->set_mode(Mode::kProfileVelocity, d); }));
  ASSERT_FALSE(wait([&](auto d) { epos->enable(d); }));
  epos->set_target(0x60FF, 0, 800);
  run_for(200ms);
  master.set_heartbeat_period(0ms);  // the master "dies"
  run_for(600ms);
  EXPECT_EQ(epos_sim.state(), State::kQuickStopActive);
  EXPECT_EQ(epos_sim.velocity(), 0);
  ASSERT_FALSE(events.empty());
  EXPECT_EQ(events.front().kind, DriveEventKind::kEmcy);
  EXPECT_EQ(events.front().emcy_code, 0x8130);
}

TEST_F(DriveTest, RebootOfADriveIsReportedAndItMustBootAgain) {
  auto epos = make(epos_config());
  ASSERT_FALSE(wait([&](auto d) { epos->boot(d); }));
  master.nmt(NmtCommand::kResetNode, 1);
  run_for(10ms);
  ASSERT_FALSE(events.empty());
  EXPECT_EQ(events.back().kind, DriveEventKind::kRebooted);
  EXPECT_FALSE(epos->booted());
  ASSERT_FALSE(wait([&](auto d) { epos->boot(d); }));
}

TEST_F(DriveTest, DestroyedDriverNoLongerListens) {
  auto epos = make(epos_config());
  ASSERT_FALSE(wait([&](auto d) { epos->boot(d); }));
  epos.reset();
  // Under ASan a dangling listener would be a use-after-free here.
  epos_sim.inject_fault(0x4210);
  epos_sim.faults().heartbeat_silent = true;
  run_for(500ms);
  EXPECT_TRUE(events.empty());
}

TEST_F(DriveTest, DriverDestroyedDuringBootLeavesNoCallbackBehind) {
  {
    Drive402 epos(master, epos_config());  // on the stack: ASan reports any later use
    epos.boot(nullptr);  // its first SDO request is on the bus, the answer not yet back
  }
  run_for(2s);  // their answers (and timeouts) must not reach the destroyed driver
  EXPECT_FALSE(master.sdo(1).busy());
  auto again = make(epos_config());
  EXPECT_FALSE(wait([&](auto d) { again->boot(d); }));
}

TEST_F(DriveTest, RebootDuringBootFailsThatBootAndTheNextOneSucceeds) {
  auto epos = make(epos_config());
  std::optional<std::error_code> r;
  epos_sim.sdo().faults().response_delay = 5ms;
  epos->boot([&](std::error_code ec) { r = ec; });
  run_for(12ms);  // the first steps of the boot
  ASSERT_FALSE(r);
  epos_sim.sdo().faults().response_delay = 0ms;
  master.nmt(NmtCommand::kResetNode, 1);
  for (int i = 0; i < 3000 && !r; ++i) tick();
  ASSERT_TRUE(r);
  EXPECT_EQ(*r, make_error_code(AxisError::kCancelled));
  EXPECT_NE(epos->boot_error().find("drive rebooted during boot"), std::string::npos) << epos->boot_error();
  EXPECT_FALSE(wait([&](auto d) { epos->boot(d); }));
  EXPECT_TRUE(epos->booted());
}

TEST_F(DriveTest, MotionWatchdogQuickStopsAfterOneSecondWithoutCommands) {
  auto epos = make(epos_config());
  ASSERT_FALSE(wait([&](auto d) { epos->boot(d); }));
  ASSERT_FALSE(wait([&](auto d) { epos->set_mode(Mode::kProfileVelocity, d); }));
  ASSERT_FALSE(wait([&](auto d) { epos->enable(d); }));
  MotionWatchdog dog(master, 1s, [&] { epos->quick_stop(nullptr); });
  for (int i = 0; i < 20; ++i) {  // commands every 100 ms keep it running
    epos->set_target(0x60FF, 0, 500);
    dog.feed();
    run_for(100ms);
  }
  EXPECT_EQ(epos_sim.state(), State::kOperationEnabled);
  run_for(899ms);  // 999 ms since the last command
  EXPECT_FALSE(dog.expired());
  run_for(2ms);
  EXPECT_TRUE(dog.expired());
  run_for(300ms);
  EXPECT_EQ(epos_sim.state(), State::kQuickStopActive);
  EXPECT_EQ(epos_sim.velocity(), 0);
}

}  // namespace
}  // namespace advee::canopen
