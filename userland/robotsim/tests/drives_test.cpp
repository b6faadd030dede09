// SPDX-License-Identifier: GPL-2.0
// The robot's drives coupled to the chassis: the EPOS's velocity moves the
// robot at the speed the drive units say, the IclA's shaft turns the
// steering, homing makes 0 straight ahead, and a bumper contact engages the
// PSC1's PAUSE and stops the robot at the wall. The drives are commanded the
// way an SDO download would (the dictionary's SDO-side write) and over CAN
// frames; time is a manual clock stepped with the chassis.
#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "advee/canopen/cia402.hpp"
#include "advee/robotsim/drives.hpp"
#include "advee/robotsim/sinks.hpp"
#include "test_util.hpp"

namespace advee::robotsim {
namespace {

using canopen::CanFrame;
using canopen::ManualClock;
using canopen::sim::SimulatedDrive;
namespace cw = canopen::cia402::cw;

template <typename T>
void sdo_write(SimulatedDrive& d, std::uint16_t index, std::uint8_t sub, T value) {
  std::vector<std::uint8_t> bytes(sizeof(T));
  for (std::size_t i = 0; i < sizeof(T); ++i) bytes[i] = static_cast<std::uint8_t>(static_cast<std::uint64_t>(value) >> (8 * i));
  ASSERT_EQ(d.od().write(index, sub, bytes), canopen::SdoAbort::kNone) << std::hex << index;
}

// Shutdown, switch on + enable operation; in `mode`.
void enable(SimulatedDrive& d, std::int8_t mode) {
  sdo_write<std::int8_t>(d, 0x6060, 0, mode);
  sdo_write<std::uint16_t>(d, 0x6040, 0, 0x06);
  sdo_write<std::uint16_t>(d, 0x6040, 0, 0x0F);
  ASSERT_EQ(d.state(), canopen::cia402::State::kOperationEnabled);
}

constexpr std::int8_t kPp = 1, kPv = 3, kHm = 6;

struct Rig {
  explicit Rig(DriveUnits u = {}, double x = 2, double y = 4)
      : drives(u, [this](const CanFrame& f) { sent.push_back(f); }, clock.fn()), robot(description(u, x, y), test::example_room()) {
    drives.power_on();
  }
  static RobotDescription description(const DriveUnits& u, double x, double y) {
    RobotDescription d = test::exact_robot();
    d.drives = u;
    d.start.position = {x, y};
    d.start.heading = 0;
    return d;
  }
  // Clock, drives and chassis advance together in 10 ms steps.
  void run(double seconds, const std::function<void()>& each_step = nullptr) {
    for (int i = 0; i < std::lround(seconds * 100); ++i) {
      clock.advance(std::chrono::milliseconds(10));
      drives.poll();
      const DriveMotion m = drives.motion();
      robot.step(m.speed_mps, m.steering_rad, 0.01);
      if (each_step) each_step();
    }
  }
  ManualClock clock;
  std::vector<CanFrame> sent;
  DrivePair drives;
  Robot robot;
};

TEST(DriveUnits, RpmPerMetrePerSecondOfTheExampleRobot) {
  // 60 * 26 / (2 pi 0.125): 1 m/s is 1986 motor rpm.
  EXPECT_NEAR(DriveUnits{}.rpm_per_mps(), 1986.25, 0.01);
  EXPECT_EQ(test::exact_robot().drives.propulsion_node, 1);
  EXPECT_EQ(test::exact_robot().drives.steering_node, 2);
  EXPECT_EQ(test::exact_robot().drives.steering_units_per_rad, 10000);
}

TEST(DriveCoupling, EposVelocityMovesTheChassisAtTheCommandedSpeed) {
  Rig rig;
  enable(rig.drives.epos(), kPv);
  const double rpm = 0.5 * DriveUnits{}.rpm_per_mps();  // 993 rpm
  sdo_write<std::int32_t>(rig.drives.epos(), 0x60FF, 0, static_cast<std::int32_t>(std::lround(rpm)));
  rig.run(0.2);  // the profile's 10000 rpm/s ramp takes 0.1 s
  EXPECT_NEAR(rig.drives.motion().speed_mps, 0.5, 0.001);
  EXPECT_NEAR(rig.robot.speed(), 0.5, 0.001);
  const double x0 = rig.robot.pose().position.x();
  rig.run(2.0);
  EXPECT_NEAR(rig.robot.pose().position.x() - x0, 1.0, 0.002);
  EXPECT_NEAR(rig.robot.pose().position.y(), 4.0, 1e-9);  // IclA at 0: straight
  // 0x606C reports the motor rpm back.
  EXPECT_EQ(rig.drives.epos().od().get<std::int32_t>(0x606C), std::lround(rpm));
  // Reverse.
  sdo_write<std::int32_t>(rig.drives.epos(), 0x60FF, 0, -static_cast<std::int32_t>(std::lround(rpm / 2)));
  rig.run(0.5);
  EXPECT_NEAR(rig.robot.speed(), -0.25, 0.001);
}

TEST(DriveCoupling, DisabledEposDoesNotMoveTheRobot) {
  Rig rig;
  sdo_write<std::int8_t>(rig.drives.epos(), 0x6060, 0, kPv);
  sdo_write<std::int32_t>(rig.drives.epos(), 0x60FF, 0, 1000);  // target set, power stage off
  rig.run(1.0);
  EXPECT_EQ(rig.robot.pose().position.x(), 2.0);
}

TEST(DriveCoupling, IclaPositionTurnsTheSteering) {
  Rig rig;
  enable(rig.drives.icla(), kPp);
  sdo_write<std::uint32_t>(rig.drives.icla(), 0x6081, 0, 2000);  // profile velocity, units/s
  const auto target = static_cast<std::int32_t>(std::lround(deg_to_rad(12) * 10000));  // 2094
  sdo_write<std::int32_t>(rig.drives.icla(), 0x607A, 0, target);
  sdo_write<std::uint16_t>(rig.drives.icla(), 0x6040, 0, 0x0F | cw::kNewSetPoint);
  rig.run(2.0);
  EXPECT_EQ(rig.drives.icla().od().get<std::int32_t>(0x6064), target);
  EXPECT_NEAR(rad_to_deg(rig.drives.motion().steering_rad), 12.0, 0.01);
  EXPECT_NEAR(rad_to_deg(rig.robot.steering()), 12.0, 0.01);
  // Right is negative; beyond the chassis' 30 degrees the linkage stops.
  sdo_write<std::uint16_t>(rig.drives.icla(), 0x6040, 0, 0x0F);
  sdo_write<std::int32_t>(rig.drives.icla(), 0x607A, 0, -static_cast<std::int32_t>(std::lround(deg_to_rad(40) * 10000)));
  sdo_write<std::uint16_t>(rig.drives.icla(), 0x6040, 0, 0x0F | cw::kNewSetPoint);
  rig.run(6.0);
  EXPECT_NEAR(rad_to_deg(rig.drives.motion().steering_rad), -40.0, 0.01);
  EXPECT_NEAR(rad_to_deg(rig.robot.steering()), -30.0, 1e-9);
}

TEST(DriveCoupling, SteeringTurnsTheRobotOnAnArc) {
  Rig rig;
  enable(rig.drives.icla(), kPp);
  sdo_write<std::uint32_t>(rig.drives.icla(), 0x6081, 0, 5000);
  sdo_write<std::int32_t>(rig.drives.icla(), 0x607A, 0, static_cast<std::int32_t>(std::lround(deg_to_rad(20) * 10000)));
  sdo_write<std::uint16_t>(rig.drives.icla(), 0x6040, 0, 0x0F | cw::kNewSetPoint);
  rig.run(1.0);
  enable(rig.drives.epos(), kPv);
  sdo_write<std::int32_t>(rig.drives.epos(), 0x60FF, 0, static_cast<std::int32_t>(std::lround(0.4 * DriveUnits{}.rpm_per_mps())));
  const double h0 = rig.robot.pose().heading;
  rig.run(2.0);
  // yaw rate v tan(20 deg) / 0.62 m = 0.2348 rad/s, less the 0.02 s speed ramp.
  EXPECT_NEAR(rig.robot.pose().heading - h0, 0.2348 * 2.0, 0.01);
}

TEST(DriveCoupling, HomingMakesZeroStraightAhead) {
  DriveUnits u;
  u.start_steering_deg = 5;  // the steering stood at 5 degrees left at power-on
  Rig rig(u);
  EXPECT_NEAR(rad_to_deg(rig.drives.motion().steering_rad), 5.0, 1e-9);
  EXPECT_EQ(rig.drives.icla().position(), 0);  // the counter knows nothing yet
  enable(rig.drives.icla(), kHm);
  sdo_write<std::int8_t>(rig.drives.icla(), 0x6098, 0, 17);    // search the switch
  sdo_write<std::uint32_t>(rig.drives.icla(), 0x6099, 1, 1000);  // units/s
  sdo_write<std::uint16_t>(rig.drives.icla(), 0x6040, 0, 0x0F | cw::kNewSetPoint);
  rig.run(2.0);  // 873 units at 1000/s
  EXPECT_TRUE(rig.drives.icla().od().get<std::uint16_t>(0x6041) & canopen::cia402::sw::kHomingAttained);
  // The switch latched the counter at its edge; the shaft coasts to a stop
  // within one 1 ms dynamics step past it (1 unit at 1000 units/s).
  EXPECT_NEAR(rad_to_deg(rig.drives.motion().steering_rad), 0.0, 0.01);
  EXPECT_NEAR(rig.drives.icla().position(), rig.drives.motion().steering_rad * 10000, 1e-6);
  EXPECT_NEAR(rig.drives.icla().od().get<std::int32_t>(0x6064), 0, 1);
  // From now on 0x607A is the steering angle.
  sdo_write<std::int8_t>(rig.drives.icla(), 0x6060, 0, kPp);
  sdo_write<std::uint16_t>(rig.drives.icla(), 0x6040, 0, 0x0F);
  sdo_write<std::int32_t>(rig.drives.icla(), 0x607A, 0, -1000);
  sdo_write<std::uint16_t>(rig.drives.icla(), 0x6040, 0, 0x0F | cw::kNewSetPoint);
  rig.run(2.0);
  EXPECT_NEAR(rig.drives.motion().steering_rad, -0.1, 1e-4);
}

TEST(DriveCoupling, HomeSwitchOffCentreStillHomesToStraightAhead) {
  DriveUnits u;
  u.home_switch_deg = -8;  // switch on the right; the drive's home offset puts 0 ahead
  u.start_steering_deg = 3;
  Rig rig(u);
  enable(rig.drives.icla(), kHm);
  sdo_write<std::int8_t>(rig.drives.icla(), 0x6098, 0, 17);
  sdo_write<std::uint32_t>(rig.drives.icla(), 0x6099, 1, 2000);
  sdo_write<std::uint16_t>(rig.drives.icla(), 0x6040, 0, 0x0F | cw::kNewSetPoint);
  rig.run(2.0);
  EXPECT_NEAR(rad_to_deg(rig.drives.motion().steering_rad), -8.0, 0.02);  // one 1 ms step at 2000 units/s
  // 0x607C is whole units: -8 degrees is -1396.26, the offset -1396.
  EXPECT_NEAR(rig.drives.icla().position(), rig.drives.motion().steering_rad * 10000, 0.5);
  sdo_write<std::int8_t>(rig.drives.icla(), 0x6060, 0, kPp);
  sdo_write<std::uint16_t>(rig.drives.icla(), 0x6040, 0, 0x0F);
  sdo_write<std::int32_t>(rig.drives.icla(), 0x607A, 0, 0);
  sdo_write<std::uint16_t>(rig.drives.icla(), 0x6040, 0, 0x0F | cw::kNewSetPoint);
  rig.run(3.0);
  EXPECT_NEAR(rig.drives.motion().steering_rad * 10000, 0.0, 0.5);
}

TEST(DriveCoupling, FramesReachTheDriveTheyAreAddressedTo) {
  Rig rig;
  rig.sent.clear();
  // SDO expedited download to node 2: 0x6060 = 1 (profile position).
  rig.drives.handle(canopen::make_frame(0x602, {0x2F, 0x60, 0x60, 0x00, 0x01, 0, 0, 0}));
  EXPECT_EQ(rig.drives.icla().od().get<std::int8_t>(0x6061), 1);
  EXPECT_EQ(rig.drives.epos().od().get<std::int8_t>(0x6061), 0);
  ASSERT_EQ(rig.sent.size(), 1u);
  EXPECT_EQ(rig.sent[0].id, 0x582u);  // the IclA's answer
  // NMT start all: both operational.
  rig.drives.handle(canopen::make_frame(0x000, {0x01, 0x00}));
  EXPECT_EQ(rig.drives.epos().nmt_state(), canopen::NmtState::kOperational);
  EXPECT_EQ(rig.drives.icla().nmt_state(), canopen::NmtState::kOperational);
}

TEST(DriveCoupling, BumperEngagesPsc1PauseAndTheRobotStopsAtTheWall) {
  // 8.9 m east: the front bumper (0.9 m) is 0.2 m from the wall at x = 10.
  Rig rig({}, 8.9, 4);
  std::vector<std::string> sent;
  Rs485SimSink sink(Rs485Devices{}, rig.robot.description(), [&](const std::string& c) { sent.push_back(c); });
  enable(rig.drives.epos(), kPv);
  sdo_write<std::int32_t>(rig.drives.epos(), 0x60FF, 0, static_cast<std::int32_t>(std::lround(0.5 * DriveUnits{}.rpm_per_mps())));
  int step = 0;
  double max_x = 0;
  const auto publish = [&] {
    max_x = std::max(max_x, rig.robot.pose().position.x());
    if (++step % 10 == 0) sink.publish(rig.robot.sense());  // 10 Hz
  };
  rig.run(2.0, publish);  // would be 1 m: through the wall
  EXPECT_LE(max_x, 9.1);  // never past the contact pose
  EXPECT_GT(rig.robot.pose().position.x(), 9.09);
  EXPECT_EQ(rig.robot.pause_sources(), kPauseFrontBumper);
  EXPECT_FALSE(rig.robot.motor_powered());
  EXPECT_EQ(rig.robot.speed(), 0);
  auto has = [&](const std::string& c) { return std::find(sent.begin(), sent.end(), c) != sent.end(); };
  EXPECT_TRUE(has("event power:psc1@0x01 pause 1 1"));
  EXPECT_TRUE(has("set a:sd1@0x10 pause 1"));
  EXPECT_FALSE(has("event power:psc1@0x01 pause 0 0"));
  // driver_canbus's answer to LL_EVENT_STOP: quick stop. The bumper is
  // released once the drive no longer pushes, and PAUSE with it.
  sdo_write<std::uint16_t>(rig.drives.epos(), 0x6040, 0, 0x02);
  rig.run(1.0, publish);
  EXPECT_EQ(rig.drives.epos().velocity(), 0);
  EXPECT_EQ(rig.robot.pause_sources(), 0);
  EXPECT_TRUE(has("event power:psc1@0x01 pause 0 0"));
  EXPECT_LE(max_x, 9.1);
}

}  // namespace
}  // namespace advee::robotsim
