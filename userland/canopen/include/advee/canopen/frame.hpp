// SPDX-License-Identifier: GPL-2.0
// Classic CAN frame as the protocol engine sees it, and the CANopen
// predefined connection set (CiA 301, 11-bit identifiers).
#pragma once

#include <array>
#include <cstdint>
#include <functional>
#include <span>
#include <string>

namespace advee::canopen {

struct CanFrame {
  std::uint32_t id = 0;  // 11-bit identifier
  std::uint8_t len = 0;  // 0..8
  bool rtr = false;
  std::array<std::uint8_t, 8> data{};

  std::span<const std::uint8_t> payload() const { return {data.data(), len}; }
  friend bool operator==(const CanFrame& a, const CanFrame& b) {
    if (a.id != b.id || a.len != b.len || a.rtr != b.rtr) return false;
    for (std::uint8_t i = 0; i < a.len && i < 8; ++i)
      if (a.data[i] != b.data[i]) return false;
    return true;
  }
};

// Builds a frame from a list of bytes (at most 8 are used).
CanFrame make_frame(std::uint32_t id, std::initializer_list<std::uint8_t> bytes);

// candump-like text: "123#11223344" (RTR: "123#R").
std::string to_string(const CanFrame& f);

// The engine never touches a socket: everything it transmits goes through this.
using FrameSender = std::function<void(const CanFrame&)>;

namespace cob {
inline constexpr std::uint32_t kNmt = 0x000;
inline constexpr std::uint32_t kSync = 0x080;
inline constexpr std::uint32_t kEmcyBase = 0x080;
inline constexpr std::uint32_t kTime = 0x100;
inline constexpr std::uint32_t kTpdoBase[4] = {0x180, 0x280, 0x380, 0x480};
inline constexpr std::uint32_t kRpdoBase[4] = {0x200, 0x300, 0x400, 0x500};
inline constexpr std::uint32_t kSdoTx = 0x580;  // server -> client
inline constexpr std::uint32_t kSdoRx = 0x600;  // client -> server
inline constexpr std::uint32_t kNmtErrorControl = 0x700;
}  // namespace cob

inline constexpr bool is_valid_node_id(unsigned n) { return n >= 1 && n <= 127; }

}  // namespace advee::canopen
