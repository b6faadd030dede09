// SPDX-License-Identifier: GPL-2.0
#include "advee/canopen/frame.hpp"

#include <cstdio>

namespace advee::canopen {

CanFrame make_frame(std::uint32_t id, std::initializer_list<std::uint8_t> bytes) {
  CanFrame f;
  f.id = id;
  for (auto b : bytes) {
    if (f.len == 8) break;
    f.data[f.len++] = b;
  }
  return f;
}

std::string to_string(const CanFrame& f) {
  char buf[40];
  int n = std::snprintf(buf, sizeof buf, "%03X#", static_cast<unsigned>(f.id));
  if (f.rtr) return std::string(buf, static_cast<std::size_t>(n)) + "R";
  for (std::uint8_t i = 0; i < f.len && i < 8; ++i)
    n += std::snprintf(buf + n, sizeof buf - static_cast<std::size_t>(n), "%02X", f.data[i]);
  return std::string(buf, static_cast<std::size_t>(n));
}

}  // namespace advee::canopen
