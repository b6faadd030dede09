// SPDX-License-Identifier: GPL-2.0
// Test helpers: an LCM message as the bytes that arrive on the bus, and
// fed to the model as the bus would.
#pragma once

#include <cstdint>
#include <vector>

#include "advee/diagcenter/model.hpp"

namespace advee::diagcenter::test {

template <typename Msg>
std::vector<std::uint8_t> encode(const Msg& m) {
  std::vector<std::uint8_t> b(static_cast<std::size_t>(m.getEncodedSize()));
  m.encode(b.data(), 0, static_cast<int>(b.size()));
  return b;
}

// feed: MSG arrives on channel CH at time NOW; true when the model took it.
template <typename Msg>
bool feed(Model& m, const char* ch, const Msg& msg, double now) {
  const auto b = encode(msg);
  return m.handle(ch, b.data(), b.size(), now);
}

}  // namespace advee::diagcenter::test
