// SPDX-License-Identifier: GPL-2.0
#include "advee/module/exit_code.hpp"

#include <string.h>

namespace advee::module {

int exit_code(ExitKind kind, int detail) {
  if (detail < 0 || detail > kMaxExitDetail)
    throw std::invalid_argument("exit code detail " + std::to_string(detail) + " outside 0..15");
  if (kind == ExitKind::Success && detail != 0)
    throw std::invalid_argument("success has no detail");
  return static_cast<int>(kind) + detail;
}

std::optional<DecodedExit> decode_exit_code(int code) {
  if (code == 0) return DecodedExit{ExitKind::Success, 0};
  for (ExitKind k : {ExitKind::Resource, ExitKind::Device, ExitKind::Other}) {
    const int base = static_cast<int>(k);
    if (code >= base && code <= base + kMaxExitDetail) return DecodedExit{k, code - base};
  }
  return std::nullopt;
}

std::string describe_exit_code(int code) {
  if (code >= 128 && code < 128 + 65) {
    const char* abbrev = sigabbrev_np(code - 128);
    return std::string("killed by SIG") + (abbrev ? abbrev : std::to_string(code - 128));
  }
  const auto d = decode_exit_code(code);
  if (!d) return "exit code " + std::to_string(code) + " (outside the module convention)";
  std::string s;
  switch (d->kind) {
    case ExitKind::Success: return "success";
    case ExitKind::Resource: s = "resource error"; break;
    case ExitKind::Device: s = "device error"; break;
    case ExitKind::Other: s = "other fatal error"; break;
  }
  if (d->detail) s += " " + std::to_string(d->detail);
  return s;
}

}  // namespace advee::module
