// SPDX-License-Identifier: GPL-2.0
#include "advee/diagcenter/duration.hpp"

#include <cctype>
#include <cmath>
#include <string>

namespace advee::diagcenter {

std::optional<double> parse_duration(std::string_view text) {
  const std::string s(text);
  std::size_t used = 0;
  double v;
  try {
    v = std::stod(s, &used);
  } catch (const std::exception&) {
    return std::nullopt;
  }
  if (!std::isfinite(v) || v < 0 || !std::isdigit(static_cast<unsigned char>(s[0]))) return std::nullopt;
  const std::string_view unit = text.substr(used);
  if (unit.empty() || unit == "s") return v;
  if (unit == "ms") return v / 1000;
  if (unit == "m" || unit == "min") return v * 60;
  if (unit == "h") return v * 3600;
  return std::nullopt;
}

}  // namespace advee::diagcenter
