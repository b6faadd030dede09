// SPDX-License-Identifier: GPL-2.0
// The virtual robot: Ackermann chassis driven by a propulsion speed (EPOS)
// and a steering angle (IclA), its two front-wheel encoders (BR-SO1), 16
// ultrasonic range finders and 4 infrared ground sensors (two BR-SD1), the
// beacon scanner (BR-SBS1), the bumpers and the MAX6615 temperatures.
#pragma once

#include <array>
#include <cstdint>
#include <optional>
#include <random>
#include <string>
#include <vector>

#include "advee/robotsim/drive_units.hpp"
#include "advee/robotsim/geometry.hpp"
#include "advee/robotsim/world.hpp"

namespace advee::robotsim {

struct Chassis {
  double wheelbase_m = 0.62;   // rear axle to front axle
  double track_m = 0.52;       // between the left and right front wheels
  double wheel_radius_m = 0.125;
  double ticks_per_rev = 2048;  // front-wheel encoder ticks per revolution
  double max_steering_deg = 30;  // |steering| is clamped to this
  double max_speed_mps = 1.5;    // |speed| is clamped to this
  // Footprint (rectangle) relative to the rear axle middle.
  double front_m = 0.90, rear_m = 0.25, half_width_m = 0.30;
};

// A distance sensor mounted on the robot: robot frame, beam heading.
struct RangeSensor {
  int board = 0;  // 0 = front BR-SD1, 1 = rear BR-SD1
  int index = 0;  // sensor index on that board
  Vec2 position = Vec2::Zero();
  double heading_deg = 0;
};

struct SrfModel {
  double min_m = 0.03, max_m = 6.0;  // SRF-08: nearer or farther reads "none"
  double noise_m = 0.01;             // standard deviation
  double beam_half_angle_deg = 15;   // the nearest surface inside the cone answers
  double proximity_pause_m = 0.0;    // > 0: PAUSE source 3 below this range
  std::vector<RangeSensor> sensors;
};

struct IrModel {
  double min_m = 0.04, max_m = 0.30;  // Sharp GP2Y0A41
  double ground_m = 0.12;             // distance to a flat floor
  double noise_m = 0.003;
  double pause_deviation_m = 0.05;    // PAUSE source 2 beyond this from ground_m
  std::vector<RangeSensor> sensors;
};

struct BeaconScanner {
  Vec2 position = Vec2::Zero();  // robot frame
  double max_range_m = 15;
  double noise_deg = 0.3;
};

// First-order thermal model: dT/dt = (ambient + gain * load - T) / tau, with
// load = |speed| / max_speed (propulsion) or |steering| / max_steering.
struct ThermalChannel {
  enum class Load { kPropulsion, kSteering } load = Load::kPropulsion;
  double ambient_c = 25, gain_c = 30, tau_s = 60;
};

struct RobotDescription {
  Chassis chassis;
  Pose start;
  SrfModel srf;
  IrModel ir;
  BeaconScanner scanner;
  std::vector<ThermalChannel> thermal;  // MAX6615 temp1, temp2
  DriveUnits drives;                    // the CANopen drives' units (advee-robot-sim --can)
};

RobotDescription parse_robot(const std::string& yaml_text, const std::string& name);
RobotDescription load_robot(const std::string& path);

// PAUSE source bits of BR-SD1 GET_PAUSE_SRC (specs/rs485-protocol.md).
enum PauseSource : std::uint8_t {
  kPauseFrontBumper = 1 << 0,
  kPauseRearBumper = 1 << 1,
  kPauseGround = 1 << 2,
  kPauseProximity = 1 << 3,
};

struct BeaconReading {
  std::uint8_t id;
  std::uint16_t bearing_cdeg;  // 0..35999, counter-clockwise from the heading
  std::uint8_t quality;        // 1..255, falls with distance
};

struct SensorFrame {
  double time_s = 0;
  Pose pose;
  double speed_mps = 0, steering_rad = 0;
  std::array<std::int64_t, 2> ticks{};  // left, right front wheel, since start
  std::vector<std::optional<double>> srf_m;  // in RobotDescription::srf.sensors order
  std::vector<std::optional<double>> ir_m;
  std::vector<BeaconReading> beacons;  // visible ones only
  std::uint8_t pause = 0;              // sources active now
  std::vector<double> temperature_c;
};

// Converts a bearing (radians, counter-clockwise from the heading) to the
// BR-SBS1's units: 0.01 degree in 0..35999.
std::uint16_t bearing_to_cdeg(double bearing_rad);

class Robot {
 public:
  // Keeps its own copy of the world (a map is a few dozen segments).
  Robot(RobotDescription desc, World world, std::uint32_t seed = 1);

  // Applies the drive's speed and steering (clamped to the chassis' limits)
  // for dt seconds: exact arc integration of the pose, encoder ticks, thermal
  // model. A move that would touch a wall or obstacle is not made (the robot
  // stops at its last free pose) and raises the bumper PAUSE source; the
  // bumper stays pressed while the propulsion pushes towards the obstacle.
  // While PAUSE is engaged the drive motor has no power (thesis 4.3): the
  // robot does not move, whatever the speed.
  void step(double speed_mps, double steering_rad, double dt);

  // The PAUSE line (BR-PSS2): the sources active now, the bumpers from the
  // last step, ground and proximity from the last sense().
  std::uint8_t pause_sources() const { return bumper_ | sensed_pause_; }
  bool motor_powered() const { return pause_sources() == 0; }
  // Actual speed and steering after the last step (0 speed while stopped).
  double speed() const { return speed_; }
  double steering() const { return steering_; }

  const Pose& pose() const { return pose_; }
  void set_pose(const Pose& p) { pose_ = p; }
  // Cumulative encoder ticks (exact, before rounding to whole ticks).
  const std::array<double, 2>& exact_ticks() const { return ticks_; }
  const RobotDescription& description() const { return desc_; }
  double time() const { return time_; }

  // Footprint rectangle in world coordinates at `p`.
  std::vector<Vec2> footprint(const Pose& p) const;
  // Bumper sources for a robot standing at `p` (front: contact ahead of the
  // footprint's middle, rear: behind it).
  std::uint8_t bumper_contact(const Pose& p) const;

  // Samples every sensor at the present pose (noise from the robot's generator).
  SensorFrame sense();

 private:
  std::optional<double> srf_range(const RangeSensor& s);
  RobotDescription desc_;
  World world_;
  std::mt19937 rng_;
  Pose pose_;
  double time_ = 0, speed_ = 0, steering_ = 0;
  std::array<double, 2> ticks_{};
  std::vector<double> temps_;
  std::uint8_t bumper_ = 0;
  std::uint8_t sensed_pause_ = 0;
};

}  // namespace advee::robotsim
