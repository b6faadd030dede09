// SPDX-License-Identifier: GPL-2.0
// Where the virtual robot's sensor values go (SensorSink) and where its
// drive commands come from (DriveSource). advee-robot-sim wires them to the
// simulators: advee-rs485-sim's control socket, the MAX6615 model's debugfs files.
#pragma once

#include <functional>
#include <map>
#include <memory>
#include <optional>
#include <string>

#include "advee/robotsim/robot.hpp"
#include "advee/robotsim/scripted_path.hpp"

namespace advee::robotsim {

class SensorSink {
 public:
  virtual ~SensorSink() = default;
  virtual void publish(const SensorFrame& frame) = 0;
};

struct DriveCommand {
  double speed_mps = 0, steering_rad = 0;
};

// The propulsion speed and steering angle the drives report. The simulated
// EPOS/IclA (advee-canopen-sim-drive) have no outside hook yet: ScriptedDrive
// stands in for them.
class DriveSource {
 public:
  virtual ~DriveSource() = default;
  virtual DriveCommand command(double time_s) = 0;
};

class ScriptedDrive : public DriveSource {
 public:
  explicit ScriptedDrive(ScriptedPath path) : path_(std::move(path)) {}
  DriveCommand command(double t) override {
    const PathSegment s = path_.at(t);
    return {s.speed_mps, s.steering_rad};
  }

 private:
  ScriptedPath path_;
};

// Sends the values as advee-rs485-sim control commands ("set sd1@0x10 srf 3 1.25",
// "set so1@0x20 ticks L R", "set sbs1@0x30 beacon 2 123.45 200",
// "set sd1@0x10 pause 1"), only those that changed since the last frame; the
// PAUSE line as a BR-PSC1 PAUSE event ("event psc1@0x01 pause 1 1") whenever
// the set of active sources changes (engaged while any is active).
// `send` delivers one command and throws on an error reply
// (rs485sim::control_ok in advee-robot-sim, a recorder in the tests).
struct Rs485Devices {
  std::string sd1_front = "a:sd1@0x10", sd1_rear = "a:sd1@0x11";
  std::string so1 = "a:so1@0x20", sbs1 = "b:sbs1@0x30";
  std::string psc1 = "power:psc1@0x01";  // empty: the PAUSE line is not reported
};

class Rs485SimSink : public SensorSink {
 public:
  using Send = std::function<void(const std::string& command)>;
  Rs485SimSink(Rs485Devices devices, const RobotDescription& desc, Send send);
  void publish(const SensorFrame& frame) override;

 private:
  void set(const std::string& key, const std::string& command);
  Rs485Devices dev_;
  RobotDescription desc_;
  Send send_;
  std::map<std::string, std::string> last_;  // per value key: the last command sent
  std::uint8_t last_pause_ = 0;
};

// Writes temp1/temp2 (millidegrees C) into the MAX6615 model's debugfs
// directory (/sys/kernel/debug/ts7800-sim/max6615).
class Max6615DebugfsSink : public SensorSink {
 public:
  explicit Max6615DebugfsSink(std::string dir) : dir_(std::move(dir)) {}
  void publish(const SensorFrame& frame) override;

 private:
  std::string dir_;
};

}  // namespace advee::robotsim
