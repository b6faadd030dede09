// SPDX-License-Identifier: GPL-2.0
// printf into a std::string, for the text summary and the terminal view
// (fixed-width numeric columns are easiest to read in printf notation).
#pragma once

#include <string>

namespace advee::diagcenter {

std::string strprintf(const char* fmt, ...) __attribute__((format(printf, 1, 2)));

}  // namespace advee::diagcenter
