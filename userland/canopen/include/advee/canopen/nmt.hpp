// SPDX-License-Identifier: GPL-2.0
// NMT master commands and the NMT states a node reports in its heartbeat
// (CiA 301 §7.2.8; canopen-notes.md §3.2-3.3).
#pragma once

#include <cstdint>
#include <string_view>

#include "advee/canopen/frame.hpp"

namespace advee::canopen {

enum class NmtCommand : std::uint8_t {
  kStart = 0x01,
  kStop = 0x02,
  kEnterPreOperational = 0x80,
  kResetNode = 0x81,
  kResetCommunication = 0x82,
};

enum class NmtState : std::uint8_t {
  kBootUp = 0x00,
  kStopped = 0x04,
  kOperational = 0x05,
  kPreOperational = 0x7F,
  kUnknown = 0xFF,  // nothing heard yet
};

// node 0 addresses all nodes.
CanFrame nmt_command_frame(NmtCommand cmd, std::uint8_t node);
CanFrame heartbeat_frame(std::uint8_t node, NmtState state);

std::string_view to_string(NmtState s);
std::string_view to_string(NmtCommand c);

}  // namespace advee::canopen
