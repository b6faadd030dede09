// SPDX-License-Identifier: GPL-2.0
#include "advee/canopen/pdo.hpp"

#include <cstdio>

namespace advee::canopen {

unsigned PdoMapping::total_bits() const {
  unsigned bits = 0;
  for (const auto& e : entries) bits += e.bits;
  return bits;
}

bool PdoMapping::maps(std::uint16_t index, std::uint8_t sub) const {
  for (const auto& e : entries)
    if (e.index == index && e.sub == sub) return true;
  return false;
}

std::uint16_t pdo_comm_index(PdoKind kind, unsigned number) {
  return static_cast<std::uint16_t>((kind == PdoKind::kRpdo ? 0x1400 : 0x1800) + number - 1);
}

std::uint16_t pdo_map_index(PdoKind kind, unsigned number) {
  return static_cast<std::uint16_t>((kind == PdoKind::kRpdo ? 0x1600 : 0x1A00) + number - 1);
}

std::uint32_t default_pdo_cob_id(PdoKind kind, unsigned number, std::uint8_t node) {
  if (number < 1 || number > 4) return kPdoCobInvalid;
  return (kind == PdoKind::kRpdo ? cob::kRpdoBase : cob::kTpdoBase)[number - 1] + node;
}

std::string to_string(const PdoMapping& m) {
  char buf[64];
  std::snprintf(buf, sizeof buf, "%s%u 0x%03X%s type %u:", m.kind == PdoKind::kRpdo ? "RPDO" : "TPDO", m.number,
                static_cast<unsigned>(m.can_id()), m.enabled() ? "" : " (disabled)", m.transmission_type);
  std::string s = buf;
  for (const auto& e : m.entries) {
    std::snprintf(buf, sizeof buf, " %04X:%02X/%u", e.index, e.sub, e.bits);
    s += buf;
  }
  return s;
}

std::optional<PdoCodec> PdoCodec::build(const PdoMapping& m, std::string* why) {
  auto fail = [why](const char* reason) -> std::optional<PdoCodec> {
    if (why) *why = reason;
    return std::nullopt;
  };
  if (!m.enabled()) return fail("PDO is disabled (COB-ID bit 31 set)");
  if (m.total_bits() > 64) return fail("mapping exceeds 64 bits");
  PdoCodec c;
  c.can_id_ = m.can_id();
  unsigned offset = 0;
  for (const auto& e : m.entries) {
    if (e.bits == 0) return fail("mapping entry of zero length");
    c.fields_.push_back({e, offset});
    offset += e.bits;
  }
  c.length_ = static_cast<std::uint8_t>((offset + 7) / 8);
  return c;
}

const PdoCodec::Field* PdoCodec::find(std::uint16_t index, std::uint8_t sub) const {
  for (const auto& f : fields_)
    if (f.entry.index == index && f.entry.sub == sub) return &f;
  return nullptr;
}

CanFrame PdoCodec::blank() const {
  CanFrame f;
  f.id = can_id_;
  f.len = length_;
  return f;
}

namespace {
std::uint64_t payload_bits(const CanFrame& f) {
  std::uint64_t v = 0;
  for (unsigned i = 0; i < 8; ++i) v |= static_cast<std::uint64_t>(f.data[i]) << (8 * i);
  return v;
}
std::uint64_t mask_of(unsigned bits) { return bits >= 64 ? ~0ull : ((1ull << bits) - 1); }
}  // namespace

bool PdoCodec::set(CanFrame& f, std::uint16_t index, std::uint8_t sub, std::uint64_t value) const {
  const Field* fl = find(index, sub);
  if (!fl) return false;
  const std::uint64_t mask = mask_of(fl->entry.bits) << fl->offset;
  std::uint64_t v = payload_bits(f);
  v = (v & ~mask) | ((value << fl->offset) & mask);
  for (unsigned i = 0; i < 8; ++i) f.data[i] = static_cast<std::uint8_t>(v >> (8 * i));
  return true;
}

std::optional<std::uint64_t> PdoCodec::get_unsigned(const CanFrame& f, std::uint16_t index, std::uint8_t sub) const {
  const Field* fl = find(index, sub);
  if (!fl || f.len < length_) return std::nullopt;
  return (payload_bits(f) >> fl->offset) & mask_of(fl->entry.bits);
}

std::optional<std::int64_t> PdoCodec::get_signed(const CanFrame& f, std::uint16_t index, std::uint8_t sub) const {
  auto u = get_unsigned(f, index, sub);
  if (!u) return std::nullopt;
  const unsigned bits = find(index, sub)->entry.bits;
  std::uint64_t v = *u;
  if (bits < 64 && (v >> (bits - 1)) & 1) v |= ~mask_of(bits);  // sign-extend
  return static_cast<std::int64_t>(v);
}

}  // namespace advee::canopen
