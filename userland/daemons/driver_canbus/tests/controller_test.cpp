// SPDX-License-Identifier: GPL-2.0
// DriveController against the simulated EPOS (node 1) and IclA (node 2) on
// the in-process virtual bus with a manual clock: boot, the drive units,
// clamping, the homing gate, the command-timeout quick stop, LL_EVENT_STOP,
// PAUSE/RUN, faults, heartbeat loss and a rebooted drive.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "advee/canopen/sim/drive_sim.hpp"
#include "advee/canopen/virtual_bus.hpp"
#include "advee/driver_canbus/controller.hpp"
#include "advee/driver_canbus/messages.hpp"

namespace advee::driver_canbus {
namespace {

using namespace std::chrono_literals;
using canopen::CanFrame;
using canopen::cia402::State;
namespace sim = canopen::sim;

struct Reported {
  module::Severity severity;
  int number;
  std::string text;
};

ControllerConfig robot_config() {
  ControllerConfig c;
  c.epos.wheel_radius_m = 0.125;
  c.epos.gear_ratio = 26;
  c.icla.units_per_rad = 10000;
  c.icla.profile_velocity = 20000;
  c.icla.homing_speed = 4000;
  c.icla.homing_acceleration = 10000;
  return c;
}

class ControllerTest : public testing::Test {
 protected:
  canopen::ManualClock clock;
  canopen::VirtualBus bus;
  std::size_t mport = bus.attach([this](const CanFrame& f) { master.handle(f); });
  std::size_t eport = bus.attach([this](const CanFrame& f) { epos_sim.handle(f); });
  std::size_t iport = bus.attach([this](const CanFrame& f) { icla_sim.handle(f); });
  canopen::Master master{canopen::MasterConfig{0x7F, 200ms, 100ms}, bus.sender(mport), clock.fn()};
  sim::SimulatedDrive epos_sim{sim::DriveSimConfig{1, sim::DriveProfile::kEpos}, bus.sender(eport), clock.fn()};
  // IclA: velocity in units/s; home switch 0.08 rad to the right.
  sim::SimulatedDrive icla_sim{sim::DriveSimConfig{2, sim::DriveProfile::kIcla, 1.0, -800}, bus.sender(iport),
                               clock.fn()};
  std::vector<Reported> reports;
  std::unique_ptr<DriveController> ctl;

  void SetUp() override {
    epos_sim.power_on();
    icla_sim.power_on();
    bus.deliver();
  }
  void make(ControllerConfig c = robot_config()) {
    ctl = std::make_unique<DriveController>(master, c, [this](module::Severity s, module::ErrorType, int n,
                                                              std::string t) {
      reports.push_back({s, n, std::move(t)});
    });
  }
  // Boots both drives; true when start() reported success.
  bool start(ControllerConfig c = robot_config()) {
    make(c);
    std::optional<bool> ok;
    ctl->start([&](bool r, const std::string& why) {
      ok = r;
      if (!r) start_error = why;
    });
    for (int i = 0; i < 5000 && !ok; ++i) tick();
    run(50ms);  // enable
    return ok.value_or(false);
  }
  std::string start_error;
  void tick() {
    clock.advance(1ms);
    master.poll();
    epos_sim.poll();
    icla_sim.poll();
    bus.deliver();
  }
  void run(canopen::Duration d) {
    for (auto n = std::chrono::duration_cast<std::chrono::milliseconds>(d).count(); n > 0; --n) tick();
  }
  // Commands every 100 ms for `d`, as the planner does at 10 Hz.
  void stream(double v, double s, canopen::Duration d) {
    for (auto t = 0ms; t < d; t += 100ms) {
      ctl->motion(v, s);
      run(100ms);
    }
  }
  int count(int number) const {
    int n = 0;
    for (const auto& r : reports) n += r.number == number;
    return n;
  }
  // Frames on RPDO4 of the EPOS (0x501) whose controlword is quick stop.
  int quick_stop_frames() const {
    int n = 0;
    for (const auto& f : bus.log())
      if (f.id == 0x501 && f.len >= 2 && (f.data[0] & 0x86) == 0x02) ++n;
    return n;
  }
  bool home() {
    ctl->home_steering();
    for (int i = 0; i < 10000 && !ctl->steering_homed(); ++i) tick();
    run(20ms);
    return ctl->steering_homed();
  }
};

TEST_F(ControllerTest, BootsEposInProfileVelocityAndIclaInProfilePositionBothEnabled) {
  ASSERT_TRUE(start()) << start_error;
  EXPECT_TRUE(ctl->ready());
  EXPECT_EQ(epos_sim.od().get<std::int8_t>(0x6061), 3);
  EXPECT_EQ(icla_sim.od().get<std::int8_t>(0x6061), 1);
  EXPECT_EQ(epos_sim.state(), State::kOperationEnabled);
  EXPECT_EQ(icla_sim.state(), State::kOperationEnabled);
  EXPECT_EQ(epos_sim.od().get<std::uint32_t>(0x6085), 20000u);
  const auto s = ctl->status();
  EXPECT_EQ(s.drives[0].state, "operation enabled");
  EXPECT_EQ(s.drives[1].state, "operation enabled");
  EXPECT_EQ(s.drives[0].node, 1);
  EXPECT_EQ(s.drives[1].node, 2);
  EXPECT_FALSE(s.drives[1].homed);
  EXPECT_FALSE(s.stopped) << s.stop_reason;
  EXPECT_EQ(count(kErrBooted), 2);
}

TEST_F(ControllerTest, SpeedBecomesMotorRpmThroughTheGearAndWheelAndComesBackAsMetresPerSecond) {
  ASSERT_TRUE(start());
  stream(1.0, 0, 500ms);
  // 1 m/s on a 0.125 m wheel = 1.2732 rev/s = 76.39 rpm at the wheel, x26 = 1986 rpm.
  EXPECT_EQ(epos_sim.od().get<std::int32_t>(0x60FF), 1986);
  EXPECT_NEAR(ctl->status().speed_mps, 1.0, 1e-3);
  EXPECT_DOUBLE_EQ(ctl->status().cmd_speed_mps, 1.0);
  stream(-0.3, 0, 500ms);
  EXPECT_EQ(epos_sim.od().get<std::int32_t>(0x60FF), -596);  // 595.8
  EXPECT_NEAR(ctl->status().speed_mps, -0.3, 1e-3);
}

TEST_F(ControllerTest, SpeedBeyondTheLimitIsClampedWithOneWarning) {
  auto c = robot_config();
  c.max_speed_mps = 1.5;
  ASSERT_TRUE(start(c));
  stream(3.0, 0, 300ms);
  EXPECT_EQ(epos_sim.od().get<std::int32_t>(0x60FF), 2979);  // 1.5 m/s
  EXPECT_EQ(count(kErrClamped), 1) << "one warning per episode, not one per command";
}

TEST_F(ControllerTest, SteeringIsRefusedUntilHomedThenFollowsInTenThousandUnitsPerRadian) {
  ASSERT_TRUE(start());
  stream(0.2, 0.1, 500ms);
  EXPECT_EQ(count(kErrNotHomed), 1);
  EXPECT_EQ(icla_sim.od().get<std::int32_t>(0x607A), 0) << "no steering target before homing";
  EXPECT_NEAR(ctl->status().speed_mps, 0.2, 1e-3) << "propulsion is not gated by homing";

  ASSERT_TRUE(home());
  EXPECT_EQ(icla_sim.od().get<std::int8_t>(0x6098), 19);
  EXPECT_EQ(icla_sim.od().get<std::int8_t>(0x6061), 1) << "back in profile position";
  EXPECT_NEAR(ctl->status().steering_rad, 0.0, 1e-4) << "0 = straight ahead after homing";
  EXPECT_TRUE(ctl->status().drives[1].homed);

  stream(0.2, 0.1, 800ms);
  EXPECT_EQ(icla_sim.od().get<std::int32_t>(0x607A), 1000);
  EXPECT_NEAR(ctl->status().steering_rad, 0.1, 1e-4);
  stream(0.2, -0.25, 800ms);
  EXPECT_NEAR(ctl->status().steering_rad, -0.25, 1e-4);
  EXPECT_DOUBLE_EQ(ctl->status().cmd_steering_rad, -0.25);
  EXPECT_EQ(count(kErrNotHomed), 1);
}

TEST_F(ControllerTest, SteeringBeyondThirtyDegreesIsClampedWithAWarning) {
  ASSERT_TRUE(start());
  ASSERT_TRUE(home());
  stream(0, 1.0, 800ms);
  EXPECT_EQ(icla_sim.od().get<std::int32_t>(0x607A), 5236);  // 30 deg = 0.5236 rad
  EXPECT_NEAR(ctl->status().steering_rad, 30.0 * std::numbers::pi / 180.0, 1e-4);
  stream(0, -2.0, 1200ms);
  EXPECT_EQ(icla_sim.od().get<std::int32_t>(0x607A), -5236);
  EXPECT_EQ(count(kErrClamped), 1) << "one episode of clamping";
  stream(0, 0.1, 800ms);
  stream(0, 0.9, 800ms);
  EXPECT_EQ(count(kErrClamped), 2) << "a new episode warns again";
}

TEST_F(ControllerTest, OneSecondWithoutCommandsQuickStopsThePropulsionAndTheNextCommandResumes) {
  ASSERT_TRUE(start());
  stream(0.5, 0, 2000ms);  // 10 Hz for 2 s: never a quick stop
  EXPECT_EQ(quick_stop_frames(), 0);
  EXPECT_EQ(epos_sim.state(), State::kOperationEnabled);
  ctl->motion(0.5, 0);
  run(990ms);
  EXPECT_EQ(quick_stop_frames(), 0) << "not before the timeout";
  EXPECT_EQ(epos_sim.state(), State::kOperationEnabled);
  run(20ms);
  EXPECT_GE(quick_stop_frames(), 1) << "quick-stop controlword to node 1";
  EXPECT_EQ(epos_sim.state(), State::kQuickStopActive);
  EXPECT_EQ(count(kErrCommandTimeout), 1);
  run(500ms);
  EXPECT_NEAR(ctl->status().speed_mps, 0.0, 1e-6);
  auto s = ctl->status();
  EXPECT_TRUE(s.stopped);
  EXPECT_EQ(s.stop_reason, "command timeout");
  EXPECT_DOUBLE_EQ(s.cmd_speed_mps, 0.0);
  run(3000ms);
  EXPECT_EQ(count(kErrCommandTimeout), 1) << "reported once per silence";

  stream(0.3, 0, 500ms);
  EXPECT_EQ(epos_sim.state(), State::kOperationEnabled);
  EXPECT_NEAR(ctl->status().speed_mps, 0.3, 1e-3);
  EXPECT_FALSE(ctl->status().stopped);
}

TEST_F(ControllerTest, ConfiguredTimeoutIsUsed) {
  auto c = robot_config();
  c.command_timeout = 300ms;
  ASSERT_TRUE(start(c));
  ctl->motion(0.5, 0);
  run(290ms);
  EXPECT_EQ(quick_stop_frames(), 0);
  run(20ms);
  EXPECT_GE(quick_stop_frames(), 1);
}

TEST_F(ControllerTest, StopEventQuickStopsAndHoldsUntilReleased) {
  ASSERT_TRUE(start());
  ASSERT_TRUE(home());
  stream(0.5, 0.1, 500ms);
  ctl->stop_event(true);
  run(300ms);
  EXPECT_EQ(epos_sim.state(), State::kQuickStopActive);
  EXPECT_EQ(icla_sim.state(), State::kQuickStopActive);
  EXPECT_EQ(ctl->status().stop_reason, "LL_EVENT_STOP");
  stream(0.5, 0.2, 1000ms);  // commands keep coming: refused
  EXPECT_NEAR(epos_sim.velocity(), 0.0, 1e-9);
  EXPECT_EQ(epos_sim.state(), State::kQuickStopActive);
  EXPECT_EQ(count(kErrRefused), 1);
  ctl->stop_event(false);
  run(200ms);
  EXPECT_EQ(epos_sim.state(), State::kQuickStopActive) << "release alone does not move";
  stream(0.4, 0.2, 800ms);
  EXPECT_EQ(epos_sim.state(), State::kOperationEnabled);
  EXPECT_NEAR(ctl->status().speed_mps, 0.4, 1e-3);
  EXPECT_NEAR(ctl->status().steering_rad, 0.2, 1e-4);
}

TEST_F(ControllerTest, PauseStopsTheDrivesAndSendsNothingUntilRun) {
  ASSERT_TRUE(start());
  stream(0.5, 0, 500ms);
  ctl->pause();
  run(300ms);
  EXPECT_EQ(epos_sim.state(), State::kQuickStopActive);
  EXPECT_EQ(ctl->status().stop_reason, "module paused");
  const auto rpdos = epos_sim.rpdos_received();
  stream(0.5, 0, 1500ms);
  EXPECT_EQ(epos_sim.rpdos_received(), rpdos) << "no frame to the EPOS while paused";
  EXPECT_EQ(count(kErrCommandTimeout), 0) << "a paused module does not time out";
  ctl->resume();
  stream(0.25, 0, 500ms);
  EXPECT_EQ(epos_sim.state(), State::kOperationEnabled);
  EXPECT_NEAR(ctl->status().speed_mps, 0.25, 1e-3);
}

TEST_F(ControllerTest, HomingIsRefusedWhileStopped) {
  ASSERT_TRUE(start());
  ctl->stop_event(true);
  run(100ms);
  ctl->home_steering();
  run(2000ms);
  EXPECT_FALSE(ctl->steering_homed());
  EXPECT_EQ(count(kErrRefused), 1);
}

TEST_F(ControllerTest, HomeOnStartHomesTheSteering) {
  auto c = robot_config();
  c.home_on_start = true;
  ASSERT_TRUE(start(c));
  for (int i = 0; i < 5000 && !ctl->steering_homed(); ++i) tick();
  EXPECT_TRUE(ctl->steering_homed());
}

TEST_F(ControllerTest, HomingRequestDuringStartUpHomingJoinsItAndTheHeldSteeringTargetIsApplied) {
  // The demo's overlap: home_on_start, the planner stand-in's LL_CMD_HOMING
  // while that homing runs, and its steering commands right behind it.
  auto c = robot_config();
  c.home_on_start = true;
  ASSERT_TRUE(start(c)) << start_error;
  ASSERT_FALSE(ctl->steering_homed()) << "the start-up homing still runs";
  ctl->home_steering();
  ctl->home_steering();
  stream(0.0, 0.05, 100ms);
  ctl->motion(0.0, 0.1);  // the latest target before the homing ends
  for (int i = 0; i < 10000 && !ctl->steering_homed(); ++i) tick();
  ASSERT_TRUE(ctl->steering_homed());
  run(1500ms);  // no further command: the held target alone must move the steering
  EXPECT_EQ(icla_sim.od().get<std::int32_t>(0x607A), 1000);
  EXPECT_NEAR(ctl->status().steering_rad, 0.1, 1e-4);
  EXPECT_EQ(icla_sim.od().get<std::int8_t>(0x6061), 1) << "back in profile position";
  int homing_started = 0, joined = 0;
  for (const auto& r : reports) {
    homing_started += r.number == kErrHoming && r.text == "icla (node 2): homing";
    joined += r.number == kErrHoming && r.text.find("joins") != std::string::npos;
  }
  EXPECT_EQ(homing_started, 1) << "the second request does not restart the homing";
  EXPECT_EQ(joined, 1) << "one notice for the joined request";
  EXPECT_EQ(count(kErrNotHomed), 0) << "targets during the homing are held, not refused";
  EXPECT_EQ(count(kErrDrive), 0) << "no failed set-point";

  stream(0.0, -0.2, 800ms);
  EXPECT_NEAR(ctl->status().steering_rad, -0.2, 1e-4) << "later commands follow as usual";
}

TEST_F(ControllerTest, AnUnacknowledgedSetPointIsRetriedOnceBeforeItIsReported) {
  auto c = robot_config();
  c.icla.drive.setpoint_timeout = 100ms;
  c.icla.drive.heartbeat_tolerance = 10;  // the muted IclA stays online: only its acknowledge is lost
  ASSERT_TRUE(start(c));
  ASSERT_TRUE(home());
  // The IclA's acknowledge is lost for 150 ms: the first handshake times out,
  // the second one goes through.
  bus.mute(iport, true);
  ctl->motion(0, 0.2);
  run(150ms);
  bus.mute(iport, false);
  run(1000ms);
  EXPECT_NEAR(ctl->status().steering_rad, 0.2, 1e-4);
  EXPECT_EQ(count(kErrDrive), 0);

  // Lost for both handshakes (250 ms): reported.
  bus.mute(iport, true);
  ctl->motion(0, -0.1);
  run(250ms);
  bus.mute(iport, false);
  run(200ms);
  ASSERT_EQ(count(kErrDrive), 1);
  EXPECT_EQ(count(kErrHeartbeatLost), 0);
  for (const auto& r : reports) {
    if (r.number == kErrDrive) {
      EXPECT_NE(r.text.find("did not acknowledge the set-point"), std::string::npos) << r.text;
    }
  }
}

TEST_F(ControllerTest, EmcyAndFaultAreReportedAndTheNextCommandResetsTheFault) {
  ASSERT_TRUE(start());
  stream(0.5, 0, 300ms);
  epos_sim.inject_fault(0x4210);
  run(300ms);
  EXPECT_EQ(count(kErrEmcy), 1);
  EXPECT_EQ(count(kErrFault), 1);
  auto s = ctl->status();
  EXPECT_TRUE(s.drives[0].fault);
  EXPECT_EQ(s.drives[0].error_code, 0x4210);
  EXPECT_EQ(s.drives[0].state, "fault");
  EXPECT_TRUE(s.stopped);
  EXPECT_EQ(s.stop_reason, "fault");
  stream(0.3, 0, 800ms);
  EXPECT_EQ(epos_sim.state(), State::kOperationEnabled);
  EXPECT_NEAR(ctl->status().speed_mps, 0.3, 1e-3);
  EXPECT_FALSE(ctl->status().drives[0].fault);
}

TEST_F(ControllerTest, HeartbeatLossIsReportedAndStopsThePropulsionWhenTheSteeringGoes) {
  ASSERT_TRUE(start());
  stream(0.5, 0, 500ms);
  icla_sim.faults().heartbeat_silent = true;
  run(500ms);
  EXPECT_EQ(count(kErrHeartbeatLost), 1);
  EXPECT_EQ(ctl->status().drives[1].state, "offline");
  EXPECT_EQ(epos_sim.state(), State::kQuickStopActive);
  EXPECT_EQ(ctl->status().stop_reason, "drive offline");
  icla_sim.faults().heartbeat_silent = false;
  run(300ms);
  EXPECT_EQ(count(kErrHeartbeatResumed), 1);
  stream(0.3, 0, 800ms);
  EXPECT_NEAR(ctl->status().speed_mps, 0.3, 1e-3);
}

// The master's own EMCY (0x0FF here): 0x8130 with the error register's
// communication bit while a drive's heartbeat is lost, the reset when it is back.
TEST_F(ControllerTest, AHeartbeatLossIsTheMastersOwnEmcyUntilTheDriveIsBack) {
  ASSERT_TRUE(start());
  const auto master_emcy = [this] {
    std::vector<std::array<std::uint8_t, 3>> out;
    for (const auto& f : bus.log())
      if (f.id == 0x0FF) out.push_back({f.data[0], f.data[1], f.data[2]});
    return out;
  };
  EXPECT_TRUE(master_emcy().empty()) << "no EMCY while both drives are there";
  epos_sim.faults().heartbeat_silent = true;
  icla_sim.faults().heartbeat_silent = true;
  run(500ms);
  EXPECT_EQ(count(kErrHeartbeatLost), 2);
  ASSERT_EQ(master_emcy().size(), 1u) << "one EMCY for two lost drives";
  EXPECT_EQ(master_emcy()[0], (std::array<std::uint8_t, 3>{0x30, 0x81, 0x11}));
  EXPECT_TRUE(master.error_active(canopen::kEmcyHeartbeatError));
  epos_sim.faults().heartbeat_silent = false;
  run(300ms);
  EXPECT_EQ(master_emcy().size(), 1u) << "the IclA is still lost";
  icla_sim.faults().heartbeat_silent = false;
  icla_sim.power_on();  // comes back by rebooting
  run(1000ms);
  ASSERT_EQ(master_emcy().size(), 2u);
  EXPECT_EQ(master_emcy()[1], (std::array<std::uint8_t, 3>{0x00, 0x00, 0x00}));
  EXPECT_FALSE(master.error_active(canopen::kEmcyHeartbeatError));
}

TEST_F(ControllerTest, ARebootedDriveIsBootedAgainAndMovesOnTheNextCommand) {
  ASSERT_TRUE(start());
  ASSERT_TRUE(home());
  stream(0.5, 0, 300ms);
  icla_sim.power_on();  // boot-up message: its configuration is gone
  run(1000ms);
  EXPECT_EQ(count(kErrRebooted), 1);
  EXPECT_EQ(count(kErrBooted), 3);
  EXPECT_FALSE(ctl->steering_homed()) << "a rebooted IclA lost its reference";
  EXPECT_EQ(icla_sim.state(), State::kOperationEnabled);
  EXPECT_EQ(icla_sim.od().get<std::int8_t>(0x6061), 1);
  EXPECT_EQ(epos_sim.state(), State::kQuickStopActive) << "propulsion stops when the steering reboots";

  epos_sim.power_on();
  run(1000ms);
  EXPECT_EQ(count(kErrRebooted), 2);
  EXPECT_EQ(count(kErrBooted), 4);
  EXPECT_EQ(epos_sim.od().get<std::int8_t>(0x6061), 3);
  stream(0.3, 0, 800ms);
  EXPECT_NEAR(ctl->status().speed_mps, 0.3, 1e-3);
  EXPECT_EQ(ctl->status().drives[0].state, "operation enabled");
}

TEST_F(ControllerTest, ADriveThatDoesNotAnswerFailsTheStartNamingIt) {
  bus.mute(iport, true);
  EXPECT_FALSE(start());
  EXPECT_NE(start_error.find("icla"), std::string::npos) << start_error;
  EXPECT_EQ(count(kErrBoot), 1);
  EXPECT_FALSE(ctl->ready());
}

TEST_F(ControllerTest, StatusBecomesLlDataDrives) {
  ASSERT_TRUE(start());
  stream(0.5, 0, 500ms);
  const auto m = drives_message(ctl->status());
  ASSERT_EQ(m.num_drives, 2);
  ASSERT_EQ(m.axis.size(), 2u);
  EXPECT_EQ(m.axis[0], lowlevel::data_drives_t::AXIS_PROPULSION);
  EXPECT_EQ(m.axis[1], lowlevel::data_drives_t::AXIS_STEERING);
  EXPECT_EQ(m.node[0], 1);
  EXPECT_EQ(m.node[1], 2);
  EXPECT_EQ(m.state[0], "operation enabled");
  EXPECT_NEAR(m.speed_mps, 0.5, 1e-3);
  EXPECT_DOUBLE_EQ(m.cmd_speed_mps, 0.5);
  EXPECT_FALSE(m.stopped);
  EXPECT_EQ(m.stop_reason, "");
  // It encodes (the arrays match num_drives).
  std::vector<std::uint8_t> buf(static_cast<std::size_t>(m.getEncodedSize()));
  EXPECT_EQ(m.encode(buf.data(), 0, static_cast<int>(buf.size())), static_cast<int>(buf.size()));
}

}  // namespace
}  // namespace advee::driver_canbus
