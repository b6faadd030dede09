// SPDX-License-Identifier: GPL-2.0
// The plain-text summary of `advee-diagnostic-center --text`: one block per
// period, one "topic key=value ..." line per subject, so that scripts grep
// it. Missing data reads "none"; every data line ends with age=SECONDS since
// its newest message, and stale=1 when that is older than three periods of
// the channel's nominal rate. docs/diagnostic-center.md lists the lines.
#pragma once

#include <string>

#include "advee/diagcenter/model.hpp"

namespace advee::diagcenter {

// The block for time `now` (the model's clock); `elapsed_s` is printed in
// its first line ("summary t=ELAPSED ...").
std::string text_summary(const Model& model, double now, double elapsed_s);

// "operation enabled" -> "operation_enabled": values stay one token.
std::string token(std::string s);

}  // namespace advee::diagcenter
