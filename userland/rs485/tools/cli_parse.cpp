// SPDX-License-Identifier: GPL-2.0
#include "cli_parse.hpp"

#include <cctype>
#include <cerrno>
#include <cmath>
#include <cstdio>
#include <cstdlib>

namespace advee::rs485::cli {

std::uint64_t parse_uint(const std::string& text, std::uint64_t min, std::uint64_t max, const std::string& what) {
  if (text.empty() || !std::isdigit(static_cast<unsigned char>(text[0])))
    throw UsageError(what + " '" + text + "' is not a number");
  errno = 0;
  char* end = nullptr;
  const unsigned long long v = std::strtoull(text.c_str(), &end, 0);
  if (errno || *end != '\0') throw UsageError(what + " '" + text + "' is not a number");
  if (v < min || v > max)
    throw UsageError(what + " " + text + " is out of range " + std::to_string(min) + ".." + std::to_string(max));
  return v;
}

std::uint8_t parse_address(const std::string& text, bool broadcast_ok) {
  const std::uint64_t max = broadcast_ok ? 0xFF : 0xFE;
  const std::uint64_t v = parse_uint(text, 0, UINT64_MAX, "address");
  if (v > max) throw UsageError("address " + text + " is out of range 0x00.." + (broadcast_ok ? "0xff" : "0xfe"));
  return static_cast<std::uint8_t>(v);
}

std::vector<std::uint8_t> parse_hex_bytes(const std::vector<std::string>& words) {
  std::vector<std::uint8_t> out;
  for (const auto& word : words) {
    std::string digits;
    for (std::size_t i = 0; i < word.size(); ++i) {
      const char c = word[i];
      if (c == ',' || c == ':' || c == ' ') {
        if (digits.size() % 2) throw UsageError("data '" + word + "': odd number of hex digits in a byte");
        continue;
      }
      if (c == '0' && i + 1 < word.size() && (word[i + 1] == 'x' || word[i + 1] == 'X') &&
          (i == 0 || word[i - 1] == ',' || word[i - 1] == ':')) {
        ++i;
        continue;
      }
      if (!std::isxdigit(static_cast<unsigned char>(c)))
        throw UsageError("data '" + word + "': '" + std::string(1, c) + "' is not a hex digit");
      digits.push_back(c);
    }
    if (digits.size() % 2) throw UsageError("data '" + word + "': odd number of hex digits");
    for (std::size_t i = 0; i < digits.size(); i += 2)
      out.push_back(static_cast<std::uint8_t>(std::stoul(digits.substr(i, 2), nullptr, 16)));
  }
  if (out.size() > 255) throw UsageError("data: " + std::to_string(out.size()) + " bytes, at most 255 fit a frame");
  return out;
}

std::chrono::microseconds parse_duration(const std::string& text) {
  std::size_t pos = 0;
  while (pos < text.size() && (std::isdigit(static_cast<unsigned char>(text[pos])) || text[pos] == '.')) ++pos;
  const std::string number = text.substr(0, pos), unit = text.substr(pos);
  char* end = nullptr;
  errno = 0;
  const double v = number.empty() ? -1 : std::strtod(number.c_str(), &end);
  if (number.empty() || errno || *end != '\0' || !std::isfinite(v))
    throw UsageError("duration '" + text + "' is not a number with an optional unit (us, ms, s)");
  double us_per_unit;
  if (unit.empty() || unit == "ms")
    us_per_unit = 1e3;
  else if (unit == "us")
    us_per_unit = 1;
  else if (unit == "s")
    us_per_unit = 1e6;
  else
    throw UsageError("duration '" + text + "': unknown unit '" + unit + "' (us, ms, s)");
  const double us = v * us_per_unit;
  if (us > 1e12) throw UsageError("duration '" + text + "' is too long");
  return std::chrono::microseconds(static_cast<std::int64_t>(std::llround(us)));
}

std::string hex(const std::vector<std::uint8_t>& bytes) {
  std::string out;
  char buf[4];
  for (std::size_t i = 0; i < bytes.size(); ++i) {
    std::snprintf(buf, sizeof(buf), i ? " %02x" : "%02x", bytes[i]);
    out += buf;
  }
  return out;
}

}  // namespace advee::rs485::cli
