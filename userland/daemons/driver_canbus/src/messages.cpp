// SPDX-License-Identifier: GPL-2.0
#include "advee/driver_canbus/messages.hpp"

namespace advee::driver_canbus {

lowlevel::data_drives_t drives_message(const DrivesStatus& s) {
  lowlevel::data_drives_t m{};
  m.num_drives = static_cast<std::int16_t>(s.drives.size());
  for (const auto& d : s.drives) {
    m.axis.push_back(d.axis == Axis::kPropulsion ? lowlevel::data_drives_t::AXIS_PROPULSION
                                                 : lowlevel::data_drives_t::AXIS_STEERING);
    m.node.push_back(static_cast<std::int8_t>(d.node));
    m.state.push_back(d.state);
    m.fault.push_back(d.fault);
    m.error_code.push_back(d.error_code);
    m.homed.push_back(d.homed);
  }
  m.speed_mps = s.speed_mps;
  m.steering_rad = s.steering_rad;
  m.cmd_speed_mps = s.cmd_speed_mps;
  m.cmd_steering_rad = s.cmd_steering_rad;
  m.stopped = s.stopped;
  m.stop_reason = s.stop_reason;
  return m;
}

}  // namespace advee::driver_canbus
