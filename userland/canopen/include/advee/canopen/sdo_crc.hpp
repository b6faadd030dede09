// SPDX-License-Identifier: GPL-2.0
// The CRC of SDO block transfer (CiA 301 §7.2.4.3.16): CRC-16-CCITT,
// polynomial x^16 + x^12 + x^5 + 1 (0x1021), initial value 0, no reflection
// ("123456789" gives 0x31C3). Client and simulated server share it.
#pragma once

#include <cstdint>
#include <span>

namespace advee::canopen {

std::uint16_t sdo_block_crc(std::span<const std::uint8_t> data, std::uint16_t crc = 0);

}  // namespace advee::canopen
