// SPDX-License-Identifier: GPL-2.0
#pragma once
// throw_errno: a failed system call as a std::system_error carrying errno,
// the one way the libraries report it (callers test .code() against std::errc).
#include <cerrno>
#include <system_error>

namespace advee {

[[noreturn]] inline void throw_errno(const char* what) {
  throw std::system_error(errno, std::generic_category(), what);
}

}  // namespace advee
