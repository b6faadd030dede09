// SPDX-License-Identifier: GPL-2.0
// What a browser may ask of the robot over its WebSocket, one JSON object per
// text frame (docs/web-dashboard.md "Control"):
//   {"type":"take"}  {"type":"take","force":true}  {"type":"release"}
//   {"type":"drive","speed_mps":S,"steering_rad":A}  {"type":"stop"}
//   {"type":"state","target":"driver_aux","state":"RUN|PAUSE|STOP|TERMINATE","confirmed":true}
//   {"type":"power","action":"output","output":N,"on":true,"confirmed":true}
//   {"type":"power","action":"poweroff|reboot","confirmed":true}
//   {"type":"homing","axis":"steering"}
// parse_control_request() accepts exactly these, with every value checked
// (finite, within the limits, names of the allowed characters); anything
// else is refused with a reason and never becomes an LCM message.
// C++17: bridge_server.cpp includes it.
#pragma once

#include <cstddef>
#include <cstdint>
#include <optional>
#include <string>
#include <string_view>

namespace advee::web {

inline constexpr std::size_t kMaxControlMessageBytes = 1024;

struct DriveLimits {
  double max_speed_mps = 0.5;
  double max_steering_rad = 0.5236;  // 30 degrees
};

struct ControlRequest {
  enum class Kind { take, release, drive, stop, state, power, homing };
  enum class PowerAction { output, poweroff, reboot };
  Kind kind = Kind::stop;
  bool force = false;           // take: over another operator
  double speed_mps = 0;         // drive
  double steering_rad = 0;      // drive
  std::string target;           // state: module name or "*"
  std::int8_t state = 0;        // state: common.data_state_t value
  PowerAction power = PowerAction::output;
  std::int8_t output = 0;       // power output: PSC1 output 0..kMaxPowerOutput
  bool on = false;              // power output
  std::string cause;            // stop sent by the bridge itself: why (take-over, ...)
};

inline constexpr int kMaxPowerOutput = 15;

struct ParsedControl {
  std::optional<ControlRequest> request;
  std::string error;  // why not, when there is no request
};

ParsedControl parse_control_request(std::string_view text, const DriveLimits& limits);

// One line for logs and CM_DATA_ERROR notices, e.g. "state driver_aux RUN".
std::string describe_request(const ControlRequest& r);

}  // namespace advee::web
