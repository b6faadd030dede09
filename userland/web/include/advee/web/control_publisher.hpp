// SPDX-License-Identifier: GPL-2.0
// Turns the bridge's accepted control requests into the stack's messages:
// drive/stop -> LL_CMD_MOTION, state -> CM_CMD_STATE (manual: an operator's
// command), power -> LL_CMD_POWER, homing -> LL_CMD_HOMING. Audited requests
// also go to the log (the journal under systemd) and out as a CM_DATA_ERROR
// notice naming the operator.
#pragma once

#include <functional>
#include <memory>
#include <string>

#include "advee/web/bridge_server.hpp"

namespace lcm {
class LCM;
}

namespace advee::web {

// The sender name on LCM.
inline constexpr const char* kWebModuleName = "advee-web";

class ControlPublisher {
 public:
  using Log = std::function<void(const std::string&)>;
  // `url` "" = the robot's bus; throws msgs::BusUnavailable.
  ControlPublisher(const std::string& url, Log log);
  ~ControlPublisher();
  ControlPublisher(const ControlPublisher&) = delete;
  ControlPublisher& operator=(const ControlPublisher&) = delete;

  void operator()(const ControlRequest& r, const Operator& who, bool audit);

 private:
  std::unique_ptr<lcm::LCM> lcm_;
  Log log_;
};

}  // namespace advee::web
