// SPDX-License-Identifier: GPL-2.0
#include "advee/diagcenter/commands.hpp"

#include "advee/module/time.hpp"
#include "advee/msgs/channels.hpp"
#include "common/cmd_state_t.hpp"
#include "lowlevel/cmd_homing_t.hpp"
#include "lowlevel/cmd_motion_t.hpp"
#include "lowlevel/cmd_power_t.hpp"

namespace advee::diagcenter {

namespace {
std::string channel(std::string_view n) { return std::string(n); }
}  // namespace

bool LcmCommandSink::motion(double speed_mps, double steering_rad) {
  lowlevel::cmd_motion_t m{};
  m.utime = module::utime_now();
  m.module = sender_;
  m.speed_mps = speed_mps;
  m.steering_rad = steering_rad;
  return lcm_.publish(channel(msgs::kCmdMotion.name), &m) == 0;
}

bool LcmCommandSink::state(const std::string& target, module::State s) {
  common::cmd_state_t c{};
  c.utime = module::utime_now();
  c.module = sender_;
  c.target = target;
  c.state = static_cast<std::int8_t>(s);
  c.manual = true;
  return lcm_.publish(channel(msgs::kCmdState.name), &c) == 0;
}

bool LcmCommandSink::power_output(int output, bool on) {
  lowlevel::cmd_power_t p{};
  p.utime = module::utime_now();
  p.module = sender_;
  p.action = lowlevel::cmd_power_t::ACTION_SET_OUTPUT;
  p.output = static_cast<std::int8_t>(output);
  p.on = on;
  return lcm_.publish(channel(msgs::kCmdPower.name), &p) == 0;
}

bool LcmCommandSink::homing_steering() {
  lowlevel::cmd_homing_t h{};
  h.utime = module::utime_now();
  h.module = sender_;
  h.axis = lowlevel::cmd_homing_t::AXIS_STEERING;
  return lcm_.publish(channel(msgs::kCmdHoming.name), &h) == 0;
}

}  // namespace advee::diagcenter
