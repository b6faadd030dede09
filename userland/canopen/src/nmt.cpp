// SPDX-License-Identifier: GPL-2.0
#include "advee/canopen/nmt.hpp"

namespace advee::canopen {

CanFrame nmt_command_frame(NmtCommand cmd, std::uint8_t node) {
  return make_frame(cob::kNmt, {static_cast<std::uint8_t>(cmd), node});
}

CanFrame heartbeat_frame(std::uint8_t node, NmtState state) {
  return make_frame(cob::kNmtErrorControl + node, {static_cast<std::uint8_t>(state)});
}

std::string_view to_string(NmtState s) {
  switch (s) {
    case NmtState::kBootUp: return "boot-up";
    case NmtState::kStopped: return "stopped";
    case NmtState::kOperational: return "operational";
    case NmtState::kPreOperational: return "pre-operational";
    case NmtState::kUnknown: break;
  }
  return "unknown";
}

std::string_view to_string(NmtCommand c) {
  switch (c) {
    case NmtCommand::kStart: return "start";
    case NmtCommand::kStop: return "stop";
    case NmtCommand::kEnterPreOperational: return "preop";
    case NmtCommand::kResetNode: return "reset-node";
    case NmtCommand::kResetCommunication: return "reset-comm";
  }
  return "?";
}

}  // namespace advee::canopen
