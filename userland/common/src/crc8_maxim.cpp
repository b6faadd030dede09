// SPDX-License-Identifier: GPL-2.0
#include "advee/crc8_maxim.hpp"

#include <array>

namespace advee {
namespace {

constexpr std::uint8_t kReflectedPoly = 0x8C;

// Same table the kernel's crc8_populate_lsb(table, 0x8C) builds, computed at
// compile time so that user space and the line discipline agree by construction.
constexpr std::array<std::uint8_t, 256> make_table() {
  std::array<std::uint8_t, 256> table{};
  for (unsigned i = 0; i < 256; ++i) {
    std::uint8_t crc = static_cast<std::uint8_t>(i);
    for (int bit = 0; bit < 8; ++bit)
      crc = static_cast<std::uint8_t>((crc & 1) ? (crc >> 1) ^ kReflectedPoly : crc >> 1);
    table[i] = crc;
  }
  return table;
}

constexpr auto kTable = make_table();

}  // namespace

std::uint8_t crc8_maxim(std::span<const std::uint8_t> data, std::uint8_t crc) noexcept {
  for (std::uint8_t byte : data) crc = kTable[crc ^ byte];
  return crc;
}

}  // namespace advee
