// SPDX-License-Identifier: GPL-2.0
// Client side of the simulator's control socket (a Unix datagram socket):
// one command, one reply. Used by advee-rs485-sim --send and by the test programs.
#pragma once

#include <chrono>
#include <string>

namespace advee::rs485sim {

// Sends `command` to the simulator listening on `socket_path` and returns its
// reply ("ok ..." or "error: ..."). Throws std::system_error when the socket
// cannot be reached or no reply comes within `timeout`.
std::string control_request(const std::string& socket_path, const std::string& command,
                            std::chrono::milliseconds timeout = std::chrono::seconds(5));

// As control_request(), but throws std::runtime_error unless the reply starts with "ok".
std::string control_ok(const std::string& socket_path, const std::string& command);

}  // namespace advee::rs485sim
