// SPDX-License-Identifier: GPL-2.0
// Exit codes of modules (thesis 3.3, advee.h module_exit_t): 0 success, a
// general kind (0x10 resource, 0x20 device, 0x40 other) plus a module-specific
// detail. The thesis allows details 1..16, but 0x10 + 16 would read as
// 0x20 (device), so details are 1..15 here and every code decodes to one kind.
// 128 + N is the shell's "killed by signal N".
#pragma once

#include <optional>
#include <stdexcept>
#include <string>

namespace advee::module {

enum class ExitKind { Success = 0x00, Resource = 0x10, Device = 0x20, Other = 0x40 };

inline constexpr int kMaxExitDetail = 15;

// kind + detail; throws std::invalid_argument for a detail outside 1..15
// (0 is allowed: the kind without detail).
int exit_code(ExitKind kind, int detail = 0);

struct DecodedExit {
  ExitKind kind;
  int detail;  // 0..15
};
// The kind of a module's exit code, nullopt for codes outside the convention
// (e.g. 1 from a crashed shell wrapper, or >= 128).
std::optional<DecodedExit> decode_exit_code(int code);
std::string describe_exit_code(int code);  // "device error 3", "killed by SIGKILL", ...

// Thrown to end a module with an exit code; Module::run() and module_main()
// report it as a fatal error and return the code.
class ModuleExit : public std::runtime_error {
 public:
  ModuleExit(ExitKind kind, int detail, const std::string& what)
      : std::runtime_error(what), code_(exit_code(kind, detail)) {}
  int code() const { return code_; }

 private:
  int code_;
};

}  // namespace advee::module
