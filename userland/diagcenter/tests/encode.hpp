// SPDX-License-Identifier: GPL-2.0
// Test helper: an LCM message as the bytes that arrive on the bus.
#pragma once

#include <cstdint>
#include <vector>

namespace advee::diagcenter::test {

template <typename Msg>
std::vector<std::uint8_t> encode(const Msg& m) {
  std::vector<std::uint8_t> b(static_cast<std::size_t>(m.getEncodedSize()));
  m.encode(b.data(), 0, static_cast<int>(b.size()));
  return b;
}

}  // namespace advee::diagcenter::test
