// SPDX-License-Identifier: GPL-2.0
#include "advee/canopen/emcy.hpp"

#include <cstdio>

#include "advee/byte_order.hpp"

namespace advee::canopen {

std::optional<Emcy> decode_emcy(const CanFrame& f) {
  if (f.rtr || f.id <= cob::kEmcyBase || f.id > cob::kEmcyBase + 127 || f.len < 3) return std::nullopt;
  Emcy e;
  e.node = static_cast<std::uint8_t>(f.id - cob::kEmcyBase);
  e.code = load_le<std::uint16_t>(f.payload().subspan(0, 2));
  e.error_register = f.data[2];
  for (std::size_t i = 0; i < 5; ++i) e.vendor[i] = f.data[3 + i];
  return e;
}

CanFrame emcy_frame(const Emcy& e) {
  CanFrame f;
  f.id = cob::kEmcyBase + e.node;
  f.len = 8;
  store_le<std::uint16_t>(std::span(f.data).subspan(0, 2), e.code);
  f.data[2] = e.error_register;
  for (std::size_t i = 0; i < 5; ++i) f.data[3 + i] = e.vendor[i];
  return f;
}

std::uint8_t error_register_bits(std::uint16_t code) {
  if (code == 0) return 0;
  std::uint8_t bits = 0x01;
  switch (code >> 12) {
    case 0x2: bits |= 0x02; break;
    case 0x3: bits |= 0x04; break;
    case 0x4: bits |= 0x08; break;
    case 0x8:
      if ((code >> 8) == 0x81 || (code >> 8) == 0x82) bits |= 0x10;
      break;
    case 0xF:
      if ((code >> 8) == 0xFF) bits |= 0x80;
      break;
    default: break;
  }
  return bits;
}

std::string_view emcy_class(std::uint16_t code) {
  switch (code >> 12) {
    case 0x0: return (code >> 8) == 0 ? "no error" : "unknown";
    case 0x1: return "generic";
    case 0x2: return "current";
    case 0x3: return "voltage";
    case 0x4: return "temperature";
    case 0x5: return "device hardware";
    case 0x6: return "device software";
    case 0x7: return "additional modules";
    case 0x8: return (code >> 8) == 0x82 ? "protocol" : "monitoring";
    case 0x9: return "external";
    case 0xF: return (code >> 8) == 0xFF ? "device specific" : "additional functions";
    default: return "unknown";
  }
}

std::string to_string(const Emcy& e) {
  char buf[96];
  std::snprintf(buf, sizeof buf, "node %u EMCY 0x%04X (%s) register 0x%02X", e.node, e.code,
                std::string(emcy_class(e.code)).c_str(), e.error_register);
  return buf;
}

}  // namespace advee::canopen
