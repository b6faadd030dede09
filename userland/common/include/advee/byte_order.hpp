// SPDX-License-Identifier: GPL-2.0
// Little-endian field helpers shared by the CANopen and RS-485 codecs (both
// protocols put multi-byte values on the wire little-endian).
#pragma once

#include <cstddef>
#include <cstdint>
#include <span>
#include <type_traits>
#include <vector>

namespace advee {

template <typename T>
  requires std::is_integral_v<T>
void store_le(std::span<std::uint8_t> out, T value) {
  auto u = static_cast<std::make_unsigned_t<T>>(value);
  for (std::size_t i = 0; i < sizeof(T) && i < out.size(); ++i)
    out[i] = static_cast<std::uint8_t>(u >> (8 * i));
}

// Reads sizeof(T) bytes, or fewer if the span is shorter (missing bytes are
// zero for unsigned types and sign-extended from the last byte for signed ones).
template <typename T>
  requires std::is_integral_v<T>
T load_le(std::span<const std::uint8_t> in) {
  using U = std::make_unsigned_t<T>;
  U u = 0;
  const std::size_t n = in.size() < sizeof(T) ? in.size() : sizeof(T);
  for (std::size_t i = 0; i < n; ++i) u |= static_cast<U>(static_cast<U>(in[i]) << (8 * i));
  if constexpr (std::is_signed_v<T>) {
    if (n > 0 && n < sizeof(T) && (in[n - 1] & 0x80))
      for (std::size_t i = n; i < sizeof(T); ++i) u |= static_cast<U>(static_cast<U>(0xFF) << (8 * i));
  }
  return static_cast<T>(u);
}

template <typename T>
  requires std::is_integral_v<T>
std::vector<std::uint8_t> to_bytes(T value) {
  std::vector<std::uint8_t> v(sizeof(T));
  store_le<T>(v, value);
  return v;
}

}  // namespace advee
