// SPDX-License-Identifier: GPL-2.0
// Where the controller's commands go: LCM in the program, a recorder in the
// tests.
#pragma once

#include <lcm/lcm-cpp.hpp>
#include <string>

#include "advee/module/state.hpp"

namespace advee::diagcenter {

class CommandSink {
 public:
  virtual ~CommandSink() = default;
  virtual bool motion(double speed_mps, double steering_rad) = 0;    // LL_CMD_MOTION
  virtual bool state(const std::string& target, module::State s) = 0;  // CM_CMD_STATE, manual
  virtual bool power_output(int output, bool on) = 0;                // LL_CMD_POWER
  virtual bool homing_steering() = 0;                                // LL_CMD_HOMING
};

// Publishes on LCM as module `sender`; every CM_CMD_STATE is an operator's
// (manual = true), so STOP can be entered and left.
class LcmCommandSink final : public CommandSink {
 public:
  LcmCommandSink(lcm::LCM& lcm, std::string sender) : lcm_(lcm), sender_(std::move(sender)) {}
  bool motion(double speed_mps, double steering_rad) override;
  bool state(const std::string& target, module::State s) override;
  bool power_output(int output, bool on) override;
  bool homing_steering() override;

 private:
  lcm::LCM& lcm_;
  std::string sender_;
};

}  // namespace advee::diagcenter
