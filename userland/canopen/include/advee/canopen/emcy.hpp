// SPDX-License-Identifier: GPL-2.0
// The emergency frame 0x080 + node (canopen-notes.md §3.7): decoding for
// the consumer side, the frame and the error register for producers.
#pragma once

#include <array>
#include <cstdint>
#include <optional>
#include <string>
#include <string_view>

#include "advee/canopen/frame.hpp"

namespace advee::canopen {

struct Emcy {
  std::uint8_t node = 0;
  std::uint16_t code = 0;            // 0x0000 = error reset / no error
  std::uint8_t error_register = 0;   // object 0x1001
  std::array<std::uint8_t, 5> vendor{};

  bool is_reset() const { return code == 0; }
};

// CiA 301 error codes of the communication (0x81xx) a CANopen node reports
// about itself.
inline constexpr std::uint16_t kEmcyCanErrorPassive = 0x8120;
inline constexpr std::uint16_t kEmcyHeartbeatError = 0x8130;  // life guard or heartbeat error
inline constexpr std::uint16_t kEmcyBusOffRecovered = 0x8140;

// The bits of the error register (0x1001) an active error code sets (CiA 301
// 7.5.2.2): bit 0 (generic) for every error, plus current (1), voltage (2),
// temperature (3), communication (4: codes 0x81xx and 0x82xx) and
// manufacturer specific (7: 0xFFxx). Bit 5 (device profile) is left to the
// profile's own codes, which this function does not know. 0 for code 0.
std::uint8_t error_register_bits(std::uint16_t code);

// nullopt if the frame is not an EMCY (SYNC 0x080 is not one).
std::optional<Emcy> decode_emcy(const CanFrame& f);
CanFrame emcy_frame(const Emcy& e);
// Class of the code from its high byte, e.g. "temperature", "monitoring".
std::string_view emcy_class(std::uint16_t code);
std::string to_string(const Emcy& e);

}  // namespace advee::canopen
