// SPDX-License-Identifier: GPL-2.0
// One line of text per LCM message, for the VM tests' listeners
// (advee-daemons-probe, advee-stack-listen) and for people reading a bus:
//   CHANNEL t=MONOTONIC_S module=SENDER key=value ...
// Every channel of channels.hpp and the simulator's SIM_DATA_POSE; values
// never contain blanks (one token each), so shell tests can split on them.
#pragma once

#include <lcm/lcm-cpp.hpp>

#include <string>

namespace advee::msgs {

// The ground truth of advee-robot-sim (not a channel of the robot: not in kAllChannels).
inline constexpr const char* kSimDataPose = "SIM_DATA_POSE";

std::string describe(const lcm::ReceiveBuffer& rb, const std::string& channel);

}  // namespace advee::msgs
