// SPDX-License-Identifier: GPL-2.0
// CRC-8/MAXIM (Dallas 1-Wire): the frame check of the robot's RS-485 protocol
// (shared/specs/rs485-protocol.md): polynomial x^8+x^5+x^4+1 reflected (0x8C),
// init 0x00, no final XOR; the AVR slaves use avr-libc's _crc_ibutton_update.
#pragma once

#include <cstddef>
#include <cstdint>
#include <span>

namespace advee {

// Continue a CRC over more bytes: crc8_maxim(b, crc8_maxim(a)) == crc8_maxim(a + b).
std::uint8_t crc8_maxim(std::span<const std::uint8_t> data, std::uint8_t crc = 0) noexcept;

}  // namespace advee
