// SPDX-License-Identifier: GPL-2.0
#include "advee/web/control_publisher.hpp"

#include <lcm/lcm-cpp.hpp>

#include "advee/module/time.hpp"
#include "advee/msgs/bus.hpp"
#include "advee/msgs/channels.hpp"
#include "common/cmd_state_t.hpp"
#include "common/error_t.hpp"
#include "lowlevel/cmd_homing_t.hpp"
#include "lowlevel/cmd_motion_t.hpp"
#include "lowlevel/cmd_power_t.hpp"

namespace advee::web {

ControlPublisher::ControlPublisher(const std::string& url, Log log)
    : lcm_(msgs::open_bus(msgs::bus_url(url))), log_(std::move(log)) {}

ControlPublisher::~ControlPublisher() = default;

namespace {
template <typename T>
void publish(lcm::LCM& lcm, std::string_view channel, T& m, const ControlPublisher::Log& log) {
  m.utime = module::utime_now();
  m.module = kWebModuleName;
  if (lcm.publish(std::string(channel), &m) != 0) log("cannot publish " + std::string(channel));
}
}  // namespace

void ControlPublisher::operator()(const ControlRequest& r, const Operator& who, bool audit) {
  using K = ControlRequest::Kind;
  switch (r.kind) {
    case K::drive:
    case K::stop: {
      lowlevel::cmd_motion_t m{};
      m.speed_mps = r.kind == K::drive ? r.speed_mps : 0;
      m.steering_rad = r.kind == K::drive ? r.steering_rad : 0;
      publish(*lcm_, msgs::kCmdMotion.name, m, log_);
      break;
    }
    case K::state: {
      common::cmd_state_t m{};
      m.target = r.target;
      m.state = r.state;
      m.manual = true;
      publish(*lcm_, msgs::kCmdState.name, m, log_);
      break;
    }
    case K::power: {
      lowlevel::cmd_power_t m{};
      m.action = r.power == ControlRequest::PowerAction::output     ? lowlevel::cmd_power_t::ACTION_SET_OUTPUT
                 : r.power == ControlRequest::PowerAction::poweroff ? lowlevel::cmd_power_t::ACTION_POWEROFF
                                                                     : lowlevel::cmd_power_t::ACTION_REBOOT;
      m.output = r.output;
      m.on = r.on;
      publish(*lcm_, msgs::kCmdPower.name, m, log_);
      break;
    }
    case K::homing: {
      lowlevel::cmd_homing_t m{};
      m.axis = lowlevel::cmd_homing_t::AXIS_STEERING;
      publish(*lcm_, msgs::kCmdHoming.name, m, log_);
      break;
    }
    case K::take:
    case K::release:
      break;
  }
  if (!audit) return;
  const std::string line = "operator " + who.name + " from " + who.address + ": " + describe_request(r);
  log_("control: " + line);
  common::error_t e{};
  e.text = line;
  e.severity = common::error_t::SEVERITY_NOTICE;
  e.type = common::error_t::TYPE_UNKNOWN;
  e.file = __FILE__;
  e.line = __LINE__;
  publish(*lcm_, msgs::kDataError.name, e, log_);
}

}  // namespace advee::web
