// SPDX-License-Identifier: GPL-2.0
// EMCY consumer side: decoding of the emergency frame 0x080 + node
// (canopen-notes.md §3.7).
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

// nullopt if the frame is not an EMCY (SYNC 0x080 is not one).
std::optional<Emcy> decode_emcy(const CanFrame& f);
CanFrame emcy_frame(const Emcy& e);
// Class of the code from its high byte, e.g. "temperature", "monitoring".
std::string_view emcy_class(std::uint16_t code);
std::string to_string(const Emcy& e);

}  // namespace advee::canopen
