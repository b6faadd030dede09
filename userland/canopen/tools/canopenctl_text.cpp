// SPDX-License-Identifier: GPL-2.0
#include "canopenctl_text.hpp"

#include <cerrno>
#include <cinttypes>
#include <cstdio>
#include <cstdlib>
#include <limits>

#include "advee/byte_order.hpp"
#include "advee/canopen/emcy.hpp"
#include "advee/canopen/nmt.hpp"

namespace advee::canopen::ctl {

namespace {
[[noreturn]] void bad(const std::string& what) { throw UsageError(what); }

// The whole string as a number in `base` (0: C prefixes), or nullopt.
std::optional<unsigned long long> to_unsigned(const std::string& s, int base) {
  if (s.empty() || s[0] == '-' || s[0] == '+' || s[0] == ' ') return std::nullopt;
  errno = 0;
  char* end;
  const unsigned long long v = std::strtoull(s.c_str(), &end, base);
  if (*end || errno) return std::nullopt;
  return v;
}

std::optional<long long> to_signed(const std::string& s) {
  if (s.empty() || s[0] == ' ') return std::nullopt;
  errno = 0;
  char* end;
  const long long v = std::strtoll(s.c_str(), &end, 0);
  if (*end || errno) return std::nullopt;
  return v;
}
}  // namespace

const std::vector<SdoType>& sdo_types() {
  static const std::vector<SdoType> types = {{"u8", 1, false},  {"u16", 2, false}, {"u32", 4, false},
                                             {"u64", 8, false}, {"i8", 1, true},   {"i16", 2, true},
                                             {"i32", 4, true},  {"i64", 8, true},  {"str", 0, false},
                                             {"hex", 0, false}};
  return types;
}

std::uint8_t parse_node(const std::string& s, bool allow_all) {
  if (allow_all && s == "all") return 0;
  const auto n = to_unsigned(s, 0);
  if (!n || *n < 1 || *n > 127) bad("bad node-ID '" + s + "' (1..127" + (allow_all ? " or all)" : ")"));
  return static_cast<std::uint8_t>(*n);
}

std::pair<std::uint8_t, std::uint8_t> parse_node_range(const std::string& s) {
  const auto dash = s.find('-');
  if (dash == std::string::npos) {
    const std::uint8_t n = parse_node(s);
    return {n, n};
  }
  const auto first = to_unsigned(s.substr(0, dash), 0);
  const auto last = to_unsigned(s.substr(dash + 1), 0);
  if (!first || !last || *first < 1 || *last > 127 || *first > *last)
    bad("bad node range '" + s + "' (NODE or FIRST-LAST, 1..127)");
  return {static_cast<std::uint8_t>(*first), static_cast<std::uint8_t>(*last)};
}

PdoMapping parse_pdo_remap(std::uint8_t node, const std::string& kind, const std::string& number,
                           const std::vector<std::string>& entries) {
  PdoMapping m;
  if (kind != "rpdo" && kind != "tpdo") bad("bad PDO kind '" + kind + "' (rpdo or tpdo)");
  m.kind = kind == "rpdo" ? PdoKind::kRpdo : PdoKind::kTpdo;
  const auto n = to_unsigned(number, 10);
  if (!n || *n < 1 || *n > 4) bad("bad PDO number '" + number + "' (1..4)");
  m.number = static_cast<unsigned>(*n);
  m.cob_id = default_pdo_cob_id(m.kind, m.number, node);
  if (entries.size() > 8) bad("too many PDO entries (" + std::to_string(entries.size()) + ", at most 8)");
  for (const std::string& e : entries) {
    const auto slash = e.find('/');
    const auto bits = slash == std::string::npos ? std::nullopt : to_unsigned(e.substr(slash + 1), 10);
    if (!bits || *bits < 1 || *bits > 64) bad("bad PDO entry '" + e + "' (INDEX:SUB/BITS, 1..64 bits)");
    const auto [index, sub] = parse_object(e.substr(0, slash));
    m.entries.push_back({index, sub, static_cast<std::uint8_t>(*bits)});
  }
  if (m.total_bits() > 64) bad("PDO entries of " + std::to_string(m.total_bits()) + " bits (at most 64)");
  return m;
}

std::pair<std::uint16_t, std::uint8_t> parse_object(const std::string& s) {
  const auto colon = s.find(':');
  const auto idx = to_unsigned(s.substr(0, colon), 16);
  const auto sub = colon == std::string::npos ? std::optional<unsigned long long>(0) : to_unsigned(s.substr(colon + 1), 0);
  if (!idx || !sub || *idx > 0xFFFF || *sub > 0xFF) bad("bad object '" + s + "' (INDEX[:SUB], index in hex)");
  return {static_cast<std::uint16_t>(*idx), static_cast<std::uint8_t>(*sub)};
}

const SdoType& parse_type(const std::string& s) {
  for (const auto& t : sdo_types())
    if (s == t.name) return t;
  bad("unknown type '" + s + "' (u8 u16 u32 u64 i8 i16 i32 i64 str hex)");
}

std::vector<std::uint8_t> encode(const SdoType& t, const std::string& v) {
  if (std::string(t.name) == "str") return {v.begin(), v.end()};
  if (std::string(t.name) == "hex") {
    std::vector<std::uint8_t> out;
    if (v.size() % 2) bad("bad hex value '" + v + "' (pairs of hex digits)");
    for (std::size_t i = 0; i < v.size(); i += 2) {
      const auto b = to_unsigned(v.substr(i, 2), 16);
      if (!b || v.substr(i, 2).find_first_of("xX") != std::string::npos) bad("bad hex value '" + v + "'");
      out.push_back(static_cast<std::uint8_t>(*b));
    }
    return out;
  }
  const int bits = t.size * 8;
  std::uint64_t raw = 0;
  if (t.is_signed) {
    const auto x = to_signed(v);
    const long long lo = bits == 64 ? std::numeric_limits<long long>::min() : -(1LL << (bits - 1));
    const long long hi = bits == 64 ? std::numeric_limits<long long>::max() : (1LL << (bits - 1)) - 1;
    if (!x || *x < lo || *x > hi)
      bad("bad value '" + v + "' for " + t.name + " (" + std::to_string(lo) + ".." + std::to_string(hi) + ")");
    raw = static_cast<std::uint64_t>(*x);
  } else {
    const auto x = to_unsigned(v, 0);
    const unsigned long long hi = bits == 64 ? std::numeric_limits<unsigned long long>::max() : (1ULL << bits) - 1;
    if (!x || *x > hi) bad("bad value '" + v + "' for " + t.name + " (0.." + std::to_string(hi) + ")");
    raw = *x;
  }
  std::vector<std::uint8_t> out(8);
  store_le<std::uint64_t>(out, raw);
  out.resize(static_cast<std::size_t>(t.size));
  return out;
}

std::string format(const SdoType& t, const std::vector<std::uint8_t>& d) {
  char buf[64];
  if (std::string(t.name) == "str") return {d.begin(), d.end()};
  if (t.size == 0 || static_cast<std::size_t>(t.size) != d.size()) {
    std::string s;
    for (auto b : d) {
      std::snprintf(buf, sizeof buf, "%02X", b);
      s += buf;
    }
    return s;
  }
  std::vector<std::uint8_t> wide(d);
  wide.resize(8, 0);
  if (t.is_signed) {
    const int shift = 64 - t.size * 8;
    const auto v = static_cast<std::int64_t>(load_le<std::uint64_t>(wide) << shift) >> shift;
    std::snprintf(buf, sizeof buf, "%" PRId64, v);
  } else {
    const std::uint64_t v = load_le<std::uint64_t>(wide);
    std::snprintf(buf, sizeof buf, "%" PRIu64 " (0x%" PRIX64 ")", v, v);
  }
  return buf;
}

std::string describe_frame(const CanFrame& f) {
  std::string s = to_string(f) + "  ";
  const unsigned fn = f.id & 0x780, node = f.id & 0x7F;
  char buf[96];
  buf[0] = 0;
  if (f.id == cob::kNmt) {
    std::snprintf(buf, sizeof buf, "NMT %s node %u", std::string(to_string(static_cast<NmtCommand>(f.data[0]))).c_str(),
                  f.data[1]);
  } else if (f.id == cob::kSync) {
    std::snprintf(buf, sizeof buf, "SYNC");
  } else if (auto e = decode_emcy(f)) {
    return s + to_string(*e);
  } else if (f.id == cob::kTime) {
    std::snprintf(buf, sizeof buf, "TIME");
  } else if (auto hb = describe_heartbeat(f)) {
    return s + *hb;
  } else if (fn == 0x580 || fn == 0x600) {
    std::snprintf(buf, sizeof buf, "SDO %s node %u %04X:%02X", fn == 0x600 ? "request" : "response", node,
                  f.data[1] | (f.data[2] << 8), f.data[3]);
  } else {
    // TPDOn on 0x180 + 0x100 (n - 1), RPDOn on 0x200 + 0x100 (n - 1).
    for (unsigned n = 0; n < 4; ++n) {
      if (fn == cob::kTpdoBase[n]) std::snprintf(buf, sizeof buf, "TPDO%u node %u", n + 1, node);
      if (fn == cob::kRpdoBase[n]) std::snprintf(buf, sizeof buf, "RPDO%u node %u", n + 1, node);
    }
  }
  return s + buf;
}

std::optional<std::string> describe_heartbeat(const CanFrame& f) {
  if ((f.id & 0x780) != 0x700 || f.len != 1 || f.rtr) return std::nullopt;
  return "heartbeat node " + std::to_string(f.id & 0x7F) + " " +
         std::string(to_string(static_cast<NmtState>(f.data[0] & 0x7F)));
}

std::string describe_identity(std::uint8_t node, const Identity& id) {
  char buf[48];
  std::snprintf(buf, sizeof buf, "node %u: device type 0x%08" PRIX32, node, id.device_type);
  std::string s = buf;
  static constexpr const char* kNames[] = {"vendor", "product", "revision", "serial"};
  for (std::size_t i = 0; i < id.identity.size(); ++i) {
    if (id.identity[i])
      std::snprintf(buf, sizeof buf, ", %s 0x%08" PRIX32, kNames[i], *id.identity[i]);
    else
      std::snprintf(buf, sizeof buf, ", %s -", kNames[i]);
    s += buf;
  }
  return s;
}

}  // namespace advee::canopen::ctl
