// SPDX-License-Identifier: GPL-2.0
// Durations on the command line: "30s", "500ms", "2m", "1.5" (seconds).
#pragma once

#include <optional>
#include <string_view>

namespace advee::diagcenter {

// Seconds, or nullopt for anything else (negative, empty, unknown unit).
std::optional<double> parse_duration(std::string_view text);

}  // namespace advee::diagcenter
