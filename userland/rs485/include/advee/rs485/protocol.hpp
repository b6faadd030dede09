// SPDX-License-Identifier: GPL-2.0
// Wire constants and the frame of the robot's RS-485/EIA-422 protocol
// (shared/specs/rs485-protocol.md). These mirror kernel/include/uapi/linux/
// n_rs485.h without including it, so that installed headers stand alone;
// src/bus.cpp checks with static_asserts that both agree.
#pragma once

#include <cstdint>
#include <vector>

namespace advee::rs485 {

inline constexpr std::uint8_t kBroadcast = 0xFF;        // ADDR of a frame to every node
inline constexpr std::uint8_t kMaxNodeAddress = 0xFE;   // highest unicast address
inline constexpr std::size_t kHeaderLength = 4;          // ADDR INSTR FLAGS LEN
inline constexpr std::size_t kMaxData = 255;             // LEN is one byte

// Request flags (master to slave). RESEND is the line discipline's business.
namespace request_flag {
inline constexpr std::uint8_t kResend = 0x01;
inline constexpr std::uint8_t kNoAck = 0x02;
}  // namespace request_flag

// Response flags (slave to master).
namespace response_flag {
inline constexpr std::uint8_t kAck = 0x01;
inline constexpr std::uint8_t kUnknownInstruction = 0x02;
inline constexpr std::uint8_t kDeviceError = 0x04;
inline constexpr std::uint8_t kEvent = 0x08;
}  // namespace response_flag

// Instructions every device knows.
namespace standard_instr {
inline constexpr std::uint8_t kGetFirmwareVersion = 0xFE;  // -> major u8, minor u8
inline constexpr std::uint8_t kReset = 0xFF;               // -> ACK, then the device resets
}  // namespace standard_instr

// One frame without its CRC: what read() of the line discipline returns and
// write() takes (ADDR INSTR FLAGS LEN DATA), LEN being data.size().
struct Frame {
  std::uint8_t addr = 0;
  std::uint8_t instr = 0;
  std::uint8_t flags = 0;
  std::vector<std::uint8_t> data;

  bool is_event() const { return (flags & response_flag::kEvent) != 0; }
  friend bool operator==(const Frame&, const Frame&) = default;
};

}  // namespace advee::rs485
