// SPDX-License-Identifier: GPL-2.0
#include "advee/canopen/device_description.hpp"

#include <algorithm>
#include <cctype>
#include <cerrno>
#include <cstdio>
#include <cstdint>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <map>
#include <sstream>

namespace advee::canopen {

namespace {

std::string lower(std::string_view s) {
  std::string r(s);
  for (char& c : r) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  return r;
}

std::string_view trim(std::string_view s) {
  while (!s.empty() && std::isspace(static_cast<unsigned char>(s.front()))) s.remove_prefix(1);
  while (!s.empty() && std::isspace(static_cast<unsigned char>(s.back()))) s.remove_suffix(1);
  return s;
}

std::string hex(std::uint64_t v, int width = 4) {
  char b[24];
  std::snprintf(b, sizeof b, "0x%0*llX", width, static_cast<unsigned long long>(v));
  return b;
}

struct Key {
  std::string name;  // as written
  std::string value;
  unsigned line;
};

struct IniSection {
  std::string name;  // as written
  unsigned line;
  std::vector<Key> keys;
  const Key* find(std::string_view key) const {
    const std::string k = lower(key);
    for (const Key& e : keys)
      if (lower(e.name) == k) return &e;
    return nullptr;
  }
};

struct TypeInfo {
  std::uint16_t type;
  std::string_view name;
  unsigned bytes;  // 0: variable size
  bool is_signed;
  bool is_real;
};

// CiA 301 table 44 (static data types) as far as a value can be given for them.
constexpr TypeInfo kTypes[] = {
    {0x0001, "BOOLEAN", 1, false, false},       {0x0002, "INTEGER8", 1, true, false},
    {0x0003, "INTEGER16", 2, true, false},      {0x0004, "INTEGER32", 4, true, false},
    {0x0005, "UNSIGNED8", 1, false, false},     {0x0006, "UNSIGNED16", 2, false, false},
    {0x0007, "UNSIGNED32", 4, false, false},    {0x0008, "REAL32", 4, true, true},
    {0x0009, "VISIBLE_STRING", 0, false, false}, {0x000A, "OCTET_STRING", 0, false, false},
    {0x000B, "UNICODE_STRING", 0, false, false}, {0x000F, "DOMAIN", 0, false, false},
    {0x0010, "INTEGER24", 3, true, false},      {0x0011, "REAL64", 8, true, true},
    {0x0012, "INTEGER40", 5, true, false},      {0x0013, "INTEGER48", 6, true, false},
    {0x0014, "INTEGER56", 7, true, false},      {0x0015, "INTEGER64", 8, true, false},
    {0x0016, "UNSIGNED24", 3, false, false},    {0x0018, "UNSIGNED40", 5, false, false},
    {0x0019, "UNSIGNED48", 6, false, false},    {0x001A, "UNSIGNED56", 7, false, false},
    {0x001B, "UNSIGNED64", 8, false, false},
};

const TypeInfo* type_info(std::uint16_t t) {
  for (const TypeInfo& i : kTypes)
    if (i.type == t) return &i;
  return nullptr;
}

// CiA 306 numbers: 0x hexadecimal, a leading 0 octal, else decimal; an
// optional minus sign. Magnitudes above 64 bits are refused.
std::optional<std::int64_t> parse_number(std::string_view s, bool* too_big = nullptr) {
  s = trim(s);
  bool neg = false;
  if (!s.empty() && (s.front() == '-' || s.front() == '+')) {
    neg = s.front() == '-';
    s.remove_prefix(1);
  }
  if (s.empty()) return std::nullopt;
  unsigned base = 10;
  if (s.size() > 2 && s[0] == '0' && (s[1] == 'x' || s[1] == 'X')) {
    base = 16;
    s.remove_prefix(2);
  } else if (s.size() > 1 && s[0] == '0') {
    base = 8;
    s.remove_prefix(1);
  }
  std::uint64_t v = 0;
  for (char c : s) {
    unsigned d;
    if (c >= '0' && c <= '9') d = static_cast<unsigned>(c - '0');
    else if (c >= 'a' && c <= 'f') d = static_cast<unsigned>(c - 'a' + 10);
    else if (c >= 'A' && c <= 'F') d = static_cast<unsigned>(c - 'A' + 10);
    else return std::nullopt;
    if (d >= base) return std::nullopt;
    if (v > (UINT64_MAX - d) / base) {
      if (too_big) *too_big = true;
      return std::nullopt;
    }
    v = v * base + d;
  }
  // Values above INT64_MAX (UNSIGNED64) keep their bits; the negation is
  // done unsigned so that no magnitude overflows.
  return static_cast<std::int64_t>(neg ? 0 - v : v);
}

class Parser {
 public:
  Parser(std::string_view file, std::optional<std::uint8_t> node_id) : file_(file), forced_node_(node_id) {}

  DescriptionResult run(std::string_view text);

 private:
  void error(unsigned line, std::string msg) {
    if (errors_.size() < kMaxDescriptionErrors) errors_.push_back({file_, line, std::move(msg)});
  }
  void split(std::string_view text);
  const IniSection* section(std::string_view name) const {
    auto it = by_name_.find(lower(name));
    return it == by_name_.end() ? nullptr : &sections_[it->second];
  }
  DeviceDescription::Section plain(std::string_view name) const;
  // (index, line of its list entry)
  std::vector<std::pair<std::uint16_t, unsigned>> object_list(std::string_view name);
  void object(std::uint16_t index, unsigned listed_at);
  std::optional<OdEntry> entry(const IniSection& s, const IniSection* type_from, std::string name_fallback);
  std::optional<std::vector<std::uint8_t>> evaluate(const Key& k, const TypeInfo& t);

  std::string file_;
  std::optional<std::uint8_t> forced_node_;
  std::vector<IniSection> sections_;
  std::map<std::string, std::size_t> by_name_;  // lower-case name -> sections_
  std::vector<DescriptionError> errors_;
  DeviceDescription d_;
};

void Parser::split(std::string_view text) {
  unsigned line_no = 0;
  IniSection* cur = nullptr;
  while (!text.empty()) {
    const auto nl = text.find('\n');
    std::string_view raw = text.substr(0, nl);
    text.remove_prefix(nl == std::string_view::npos ? text.size() : nl + 1);
    ++line_no;
    const std::string_view line = trim(raw);
    if (line.empty() || line.front() == ';') continue;
    if (line.front() == '[') {
      if (line.back() != ']' || line.size() < 3) {
        error(line_no, "expected a section header '[name]', found '" + std::string(line.substr(0, 40)) + "'");
        cur = nullptr;
        continue;
      }
      const std::string name(trim(line.substr(1, line.size() - 2)));
      const std::string key = lower(name);
      if (auto it = by_name_.find(key); it != by_name_.end()) {
        error(line_no, "expected each section once; [" + name + "] is already at line " +
                           std::to_string(sections_[it->second].line));
        cur = nullptr;
        continue;
      }
      by_name_[key] = sections_.size();
      sections_.push_back({name, line_no, {}});
      cur = &sections_.back();
      continue;
    }
    const auto eq = line.find('=');
    if (eq == std::string_view::npos || eq == 0) {
      error(line_no, "expected '[section]' or 'key=value', found '" + std::string(line.substr(0, 40)) + "'");
      continue;
    }
    if (!cur) {
      error(line_no, "expected a section header before 'key=value'");
      continue;
    }
    Key k{std::string(trim(line.substr(0, eq))), std::string(trim(line.substr(eq + 1))), line_no};
    if (const Key* prev = cur->find(k.name)) {
      error(line_no, "expected each key once in [" + cur->name + "]; " + k.name + " is already at line " +
                         std::to_string(prev->line));
      continue;
    }
    cur->keys.push_back(std::move(k));
  }
}

DeviceDescription::Section Parser::plain(std::string_view name) const {
  DeviceDescription::Section out;
  if (const IniSection* s = section(name))
    for (const Key& k : s->keys) out.emplace_back(k.name, k.value);
  return out;
}

std::vector<std::pair<std::uint16_t, unsigned>> Parser::object_list(std::string_view name) {
  std::vector<std::pair<std::uint16_t, unsigned>> out;
  const IniSection* s = section(name);
  if (!s) return out;
  const Key* count = s->find("SupportedObjects");
  if (!count) {
    error(s->line, "expected SupportedObjects=<count> in [" + s->name + "]");
    return out;
  }
  const auto n = parse_number(count->value);
  if (!n || *n < 0 || *n > 0xFFFF) {
    error(count->line, "expected a count 0..65535 for SupportedObjects, found '" + count->value + "'");
    return out;
  }
  for (std::int64_t i = 1; i <= *n; ++i) {
    const Key* k = s->find(std::to_string(i));
    if (!k) {
      error(s->line, "expected " + std::to_string(i) + "=<index> in [" + s->name + "] (SupportedObjects=" +
                         std::to_string(*n) + ")");
      continue;
    }
    const auto idx = parse_number(k->value);
    if (!idx || *idx <= 0 || *idx > 0xFFFF) {
      error(k->line, "expected an object index 0x0001..0xFFFF, found '" + k->value + "'");
      continue;
    }
    out.emplace_back(static_cast<std::uint16_t>(*idx), k->line);
  }
  return out;
}

std::optional<std::vector<std::uint8_t>> Parser::evaluate(const Key& k, const TypeInfo& t) {
  const std::string_view v = trim(k.value);
  if (t.bytes == 0) {
    if (t.type == 0x0009) return std::vector<std::uint8_t>(v.begin(), v.end());
    // OCTET_STRING, UNICODE_STRING, DOMAIN: hexadecimal digits, two per byte.
    std::vector<std::uint8_t> out;
    std::string digits;
    for (char c : v)
      if (!std::isspace(static_cast<unsigned char>(c))) digits += c;
    if (digits.size() > 2 && digits[0] == '0' && (digits[1] == 'x' || digits[1] == 'X')) digits.erase(0, 2);
    if (digits.size() % 2) {
      error(k.line, "expected hexadecimal bytes (two digits each) for " + k.name + " of " + std::string(t.name) +
                        ", found '" + k.value + "'");
      return std::nullopt;
    }
    for (std::size_t i = 0; i < digits.size(); i += 2) {
      const auto b = parse_number("0x" + digits.substr(i, 2));
      if (!b) {
        error(k.line, "expected hexadecimal bytes for " + k.name + " of " + std::string(t.name) + ", found '" +
                          k.value + "'");
        return std::nullopt;
      }
      out.push_back(static_cast<std::uint8_t>(*b));
    }
    return out;
  }
  std::vector<std::uint8_t> out(t.bytes, 0);
  if (v.empty()) return out;
  if (t.is_real && v.find("0x") == std::string_view::npos && v.find("0X") == std::string_view::npos) {
    const std::string s(v);
    char* end = nullptr;
    errno = 0;
    const double d = std::strtod(s.c_str(), &end);
    if (end == s.c_str() || *end != '\0' || errno == ERANGE) {
      error(k.line, "expected a number for " + k.name + " of " + std::string(t.name) + ", found '" + k.value + "'");
      return std::nullopt;
    }
    std::uint64_t bits;
    if (t.bytes == 4) {
      const float f = static_cast<float>(d);
      std::uint32_t b32;
      std::memcpy(&b32, &f, 4);
      bits = b32;
    } else {
      std::memcpy(&bits, &d, 8);
    }
    for (unsigned i = 0; i < t.bytes; ++i) out[i] = static_cast<std::uint8_t>(bits >> (8 * i));
    return out;
  }
  // Integers: terms joined by '+', each a number or $NODEID (CiA 306 4.5.2).
  std::int64_t sum = 0;
  std::string_view rest = v;
  while (true) {
    const auto plus = rest.find('+', 1);  // a leading '+' is a sign
    const std::string_view term = trim(rest.substr(0, plus));
    std::optional<std::int64_t> n = std::int64_t{d_.node_id};
    if (lower(term) != "$nodeid") {
      bool too_big = false;
      n = parse_number(term, &too_big);
      if (!n) {
        error(k.line, "expected a number (0x hexadecimal, 0 octal, decimal) or $NODEID for " + k.name + " of " +
                          std::string(t.name) + ", found '" + k.value + "'" + (too_big ? " (above 64 bits)" : ""));
        return std::nullopt;
      }
    }
    if (__builtin_add_overflow(sum, *n, &sum)) {
      error(k.line, "expected " + k.name + " within 64 bits, found '" + k.value + "'");
      return std::nullopt;
    }
    if (plus == std::string_view::npos) break;
    rest.remove_prefix(plus + 1);
  }
  if (t.bytes < 8) {
    const unsigned bits = t.bytes * 8;
    // Signed types also take their bits in hexadecimal (0xFFFF for INTEGER16 -1).
    const std::int64_t lo = t.is_signed ? -(std::int64_t{1} << (bits - 1)) : 0;
    const std::int64_t hi = (std::int64_t{1} << bits) - 1;
    if (t.type == 0x0001 ? (sum < 0 || sum > 1) : (sum < lo || sum > hi)) {
      error(k.line, "expected " + k.name + " within the range of " + std::string(t.name) + " (" +
                        (t.type == 0x0001 ? std::string("0..1") : std::to_string(lo) + ".." + std::to_string(hi)) +
                        "), found '" + k.value + "' = " + std::to_string(sum));
      return std::nullopt;
    }
  }
  const auto u = static_cast<std::uint64_t>(sum);
  for (unsigned i = 0; i < t.bytes; ++i) out[i] = static_cast<std::uint8_t>(u >> (8 * i));
  return out;
}

// One VAR: its own section, or a sub-object's; type_from supplies DataType,
// AccessType and PDOMapping when the sub-object section does not (compact
// arrays).
std::optional<OdEntry> Parser::entry(const IniSection& s, const IniSection* type_from, std::string name_fallback) {
  auto get = [&](std::string_view key) -> const Key* {
    if (const Key* k = s.find(key)) return k;
    return type_from ? type_from->find(key) : nullptr;
  };
  OdEntry e;
  bool ok = true;
  if (const Key* n = s.find("ParameterName")) e.name = n->value;
  else if (!name_fallback.empty()) e.name = std::move(name_fallback);
  else {
    error(s.line, "expected ParameterName=<name> in [" + s.name + "]");
    ok = false;
  }
  const Key* dt = get("DataType");
  const TypeInfo* t = nullptr;
  if (!dt) {
    error(s.line, "expected DataType=<CiA 301 type index> in [" + s.name + "]");
    ok = false;
  } else if (const auto n = parse_number(dt->value); !n || !(t = type_info(static_cast<std::uint16_t>(*n))) || *n > 0xFFFF) {
    error(dt->line, "expected a CiA 301 data type (0x0001 BOOLEAN .. 0x001B UNSIGNED64) for DataType, found '" +
                        dt->value + "'");
    t = nullptr;
    ok = false;
  } else {
    e.data_type = t->type;
    e.variable_size = t->bytes == 0;
  }
  if (const Key* a = get("AccessType")) {
    e.access_text = a->value;
    const std::string l = lower(a->value);
    if (l == "ro" || l == "const") e.access = Access::kReadOnly;
    else if (l == "wo") e.access = Access::kWriteOnly;
    else if (l == "rw" || l == "rwr" || l == "rww") e.access = Access::kReadWrite;
    else {
      error(a->line, "expected AccessType ro, wo, rw, rwr, rww or const, found '" + a->value + "'");
      ok = false;
    }
  } else {
    error(s.line, "expected AccessType=<ro|wo|rw|rwr|rww|const> in [" + s.name + "]");
    ok = false;
  }
  if (const Key* p = get("PDOMapping")) {
    const auto n = parse_number(p->value);
    if (!n || (*n != 0 && *n != 1)) {
      error(p->line, "expected PDOMapping 0 or 1, found '" + p->value + "'");
      ok = false;
    }
    e.mappable = n && *n == 1;
  }
  if (const Key* k = s.find("LowLimit")) e.low_limit = k->value;
  if (const Key* k = s.find("HighLimit")) e.high_limit = k->value;
  const Key* def = s.find("DefaultValue");
  const Key* par = s.find("ParameterValue");
  if (def) e.default_text = def->value;
  if (par) e.parameter_text = par->value;
  if (!ok || !t) return std::nullopt;
  // The value is what the DCF configures, else the default.
  if (const Key* k = par ? par : def) {
    auto v = evaluate(*k, *t);
    if (!v) return std::nullopt;
    e.value = std::move(*v);
  } else {
    e.value.assign(t->bytes, 0);
  }
  return e;
}

void Parser::object(std::uint16_t index, unsigned listed_at) {
  char name[8];
  std::snprintf(name, sizeof name, "%04X", index);
  const IniSection* s = section(name);
  if (!s) {
    error(listed_at, "expected a section [" + std::string(name) + "] for object " + hex(index) + ", listed here");
    return;
  }
  OdObject obj;
  if (const Key* n = s->find("ParameterName")) obj.name = n->value;
  else error(s->line, "expected ParameterName=<name> in [" + s->name + "]");
  if (const Key* ot = s->find("ObjectType")) {
    const auto n = parse_number(ot->value);
    if (!n || (*n != 2 && *n != 5 && *n != 6 && *n != 7 && *n != 8 && *n != 9)) {
      error(ot->line, "expected ObjectType 0x7 VAR, 0x8 ARRAY, 0x9 RECORD, 0x2 DOMAIN, 0x5 DEFTYPE or 0x6 DEFSTRUCT, found '" +
                          ot->value + "'");
      return;
    }
    obj.object_type = static_cast<std::uint8_t>(*n);
  }
  if (obj.object_type != 8 && obj.object_type != 9 && obj.object_type != 6) {
    // A DOMAIN object may leave its DataType out (it is DOMAIN).
    IniSection domain_type{s->name, s->line, {{"DataType", "0x000F", s->line}}};
    if (auto e = entry(*s, obj.object_type == 2 ? &domain_type : nullptr, {})) {
      d_.od.add_entry(index, 0, std::move(*e));
      d_.od.describe(index, std::move(obj));
    }
    return;
  }
  if (const Key* c = s->find("CompactSubObj"); c && obj.object_type == 8) {
    // CiA 306 4.5.2.4: sub 0 holds the count; subs 1..n take DataType,
    // AccessType and PDOMapping from the object, values from [XXXXValue] and
    // names from [XXXXName] (else ParameterName + sub-index).
    const auto n = parse_number(c->value);
    if (!n || *n < 1 || *n > 254) {
      error(c->line, "expected CompactSubObj 1..254, found '" + c->value + "'");
      return;
    }
    OdEntry count;
    count.name = "NrOfObjects";
    count.data_type = 0x0005;
    count.access_text = "ro";
    count.access = Access::kReadOnly;
    count.default_text = std::to_string(*n);
    count.value = {static_cast<std::uint8_t>(*n)};
    d_.od.add_entry(index, 0, std::move(count));
    const IniSection* values = section(std::string(name) + "Value");
    const IniSection* names = section(std::string(name) + "Name");
    for (std::int64_t sub = 1; sub <= *n; ++sub) {
      IniSection sub_s{s->name, s->line, {}};
      const std::string key = std::to_string(sub);
      if (values)
        if (const Key* v = values->find(key)) sub_s.keys.push_back({"DefaultValue", v->value, v->line});
      const Key* nm = names ? names->find(key) : nullptr;
      auto e = entry(sub_s, s, nm ? nm->value : obj.name + std::to_string(sub));
      if (!e) return;
      d_.od.add_entry(index, static_cast<std::uint8_t>(sub), std::move(*e));
    }
    d_.od.describe(index, std::move(obj));
    return;
  }
  const Key* subs = s->find("SubNumber");
  if (!subs) {
    error(s->line, "expected SubNumber=<count> (or CompactSubObj for an ARRAY) in [" + s->name + "]");
    return;
  }
  const auto count = parse_number(subs->value);
  if (!count || *count < 1 || *count > 255) {
    error(subs->line, "expected SubNumber 1..255, found '" + subs->value + "'");
    return;
  }
  std::int64_t found = 0;
  bool ok = true;
  for (unsigned sub = 0; sub <= 0xFF; ++sub) {
    char sub_name[16];
    std::snprintf(sub_name, sizeof sub_name, "%04Xsub%X", index, sub);
    const IniSection* ss = section(sub_name);
    if (!ss) continue;
    ++found;
    if (auto e = entry(*ss, nullptr, {})) d_.od.add_entry(index, static_cast<std::uint8_t>(sub), std::move(*e));
    else ok = false;
  }
  if (found != *count) {
    error(subs->line, "expected SubNumber=" + subs->value + " sub-object sections [" + std::string(name) +
                          "subN], found " + std::to_string(found));
    return;
  }
  if (ok) d_.od.describe(index, std::move(obj));
}

DescriptionResult Parser::run(std::string_view text) {
  split(text);
  d_.file_info = plain("FileInfo");
  d_.device_info = plain("DeviceInfo");
  d_.dummy_usage = plain("DummyUsage");
  d_.commissioning = plain("DeviceComissioning");
  if (forced_node_) {
    d_.node_id = *forced_node_;
  } else if (const IniSection* c = section("DeviceComissioning")) {
    if (const Key* k = c->find("NodeID")) {
      const auto n = parse_number(k->value);
      if (!n || *n < 1 || *n > 127) error(k->line, "expected a NodeID 1..127, found '" + k->value + "'");
      else d_.node_id = static_cast<std::uint8_t>(*n);
    }
  }
  std::vector<std::pair<std::uint16_t, unsigned>> all;
  for (std::string_view list : {"MandatoryObjects", "OptionalObjects", "ManufacturerObjects"}) {
    const auto l = object_list(list);
    all.insert(all.end(), l.begin(), l.end());
  }
  if (all.empty() && errors_.empty())
    error(0, "expected objects: no [MandatoryObjects], [OptionalObjects] or [ManufacturerObjects] lists one");
  std::sort(all.begin(), all.end());
  for (std::size_t i = 0; i < all.size(); ++i) {
    if (i && all[i].first == all[i - 1].first) {
      error(all[i].second, "expected each object in one list once; " + hex(all[i].first) + " is also at line " +
                               std::to_string(all[i - 1].second));
      continue;
    }
    object(all[i].first, all[i].second);
  }
  DescriptionResult r;
  r.errors = std::move(errors_);
  if (r.errors.empty()) r.description = std::move(d_);
  return r;
}

}  // namespace

std::string DescriptionError::text() const {
  // GNU style: "file:line: message", "file: message" for the whole file.
  return line == 0 ? file + ": " + message : file + ":" + std::to_string(line) + ": " + message;
}

std::optional<std::string> DeviceDescription::value(const Section& s, std::string_view key) {
  const std::string k = lower(key);
  for (const auto& [name, v] : s)
    if (lower(name) == k) return v;
  return std::nullopt;
}

bool same_model(const DeviceDescription& a, const DeviceDescription& b) {
  return a.file_info == b.file_info && a.device_info == b.device_info && a.dummy_usage == b.dummy_usage &&
         a.commissioning == b.commissioning && a.node_id == b.node_id && a.od.entries() == b.od.entries() &&
         a.od.objects() == b.od.objects();
}

DescriptionResult parse_device_description(std::string_view text, std::string_view file_name,
                                           std::optional<std::uint8_t> node_id) {
  return Parser(file_name, node_id).run(text);
}

DescriptionResult load_device_description(const std::string& path, std::optional<std::uint8_t> node_id) {
  std::ifstream in(path, std::ios::binary);
  if (!in) {
    DescriptionResult r;
    r.errors.push_back({path, 0, std::string("expected a readable file: ") + std::strerror(errno)});
    return r;
  }
  std::ostringstream text;
  text << in.rdbuf();
  return parse_device_description(text.str(), path, node_id);
}

std::string_view data_type_name(std::uint16_t data_type) {
  const TypeInfo* t = type_info(data_type);
  return t ? t->name : std::string_view{};
}

namespace {

// Entries added in code have no texts: these stand in for them.
std::string value_text(const OdEntry& e) {
  if (e.data_type || e.value.empty()) return e.default_text;
  if (e.data_type == 0x0009) return std::string(e.value.begin(), e.value.end());
  std::uint64_t v = 0;
  for (std::size_t i = 0; i < e.value.size() && i < 8; ++i) v |= std::uint64_t{e.value[i]} << (8 * i);
  return hex(v, 0);
}

std::uint16_t type_of(const OdEntry& e) {
  if (e.data_type) return e.data_type;
  if (e.variable_size) return 0x000F;
  switch (e.value.size()) {
    case 1: return 0x0005;
    case 2: return 0x0006;
    case 8: return 0x001B;
    default: return 0x0007;
  }
}

std::string access_of(const OdEntry& e) {
  if (!e.access_text.empty()) return e.access_text;
  return e.access == Access::kReadOnly ? "ro" : e.access == Access::kWriteOnly ? "wo" : "rw";
}

void write_var(std::ostringstream& o, const OdEntry& e, std::uint8_t object_type = 7) {
  o << "ParameterName=" << e.name << "\n";
  o << "ObjectType=" << hex(object_type, 0) << "\n";
  o << "DataType=" << hex(type_of(e)) << "\n";
  o << "AccessType=" << access_of(e) << "\n";
  o << "DefaultValue=" << value_text(e) << "\n";
  o << "PDOMapping=" << (e.mappable ? 1 : 0) << "\n";
  if (!e.low_limit.empty()) o << "LowLimit=" << e.low_limit << "\n";
  if (!e.high_limit.empty()) o << "HighLimit=" << e.high_limit << "\n";
  if (e.parameter_text) o << "ParameterValue=" << *e.parameter_text << "\n";
}

void write_section(std::ostringstream& o, std::string_view name, const DeviceDescription::Section& s) {
  if (s.empty()) return;
  o << "[" << name << "]\n";
  for (const auto& [k, v] : s) o << k << "=" << v << "\n";
  o << "\n";
}

}  // namespace

std::string write_dcf(const DeviceDescription& d) {
  std::ostringstream o;
  write_section(o, "FileInfo", d.file_info);
  write_section(o, "DeviceInfo", d.device_info);
  write_section(o, "DummyUsage", d.dummy_usage);
  write_section(o, "DeviceComissioning", d.commissioning);
  std::vector<std::uint16_t> indices;
  for (const auto& [key, e] : d.od.entries())
    if (indices.empty() || indices.back() != key.first) indices.push_back(key.first);
  std::vector<std::uint16_t> lists[3];
  for (std::uint16_t i : indices) {
    if (i == 0x1000 || i == 0x1001 || i == 0x1018) lists[0].push_back(i);
    else if (i >= 0x2000 && i <= 0x5FFF) lists[2].push_back(i);
    else lists[1].push_back(i);
  }
  const char* names[3] = {"MandatoryObjects", "OptionalObjects", "ManufacturerObjects"};
  for (int l = 0; l < 3; ++l) {
    o << "[" << names[l] << "]\nSupportedObjects=" << lists[l].size() << "\n";
    for (std::size_t i = 0; i < lists[l].size(); ++i) o << i + 1 << "=" << hex(lists[l][i]) << "\n";
    o << "\n";
  }
  char head[24];
  for (std::uint16_t index : indices) {
    const OdObject* obj = d.od.object(index);
    const auto first = d.od.entries().lower_bound({index, 0});
    auto last = first;
    std::size_t subs = 0;
    while (last != d.od.entries().end() && last->first.first == index) ++last, ++subs;
    const std::uint8_t type = obj ? obj->object_type : (subs == 1 && first->first.second == 0 ? 7 : 9);
    std::snprintf(head, sizeof head, "[%04X]\n", index);
    o << head;
    if (type != 8 && type != 9 && type != 6) {
      OdEntry e = first->second;
      if (obj) e.name = obj->name;
      write_var(o, e, type);
      o << "\n";
      continue;
    }
    o << "ParameterName=" << (obj ? obj->name : std::string()) << "\n";
    o << "ObjectType=" << hex(type, 0) << "\n";
    o << "SubNumber=" << subs << "\n\n";
    for (auto it = first; it != last; ++it) {
      std::snprintf(head, sizeof head, "[%04Xsub%X]\n", index, it->first.second);
      o << head;
      write_var(o, it->second);
      o << "\n";
    }
  }
  return o.str();
}

}  // namespace advee::canopen
