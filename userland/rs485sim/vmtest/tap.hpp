// SPDX-License-Identifier: GPL-2.0
// TAP 13 output of the C++ programs that the VM suite tests/vm/rs485 runs.
#pragma once

#include <cstdarg>
#include <cstdio>
#include <string>

namespace advee::rs485sim::vmtest {

class Tap {
 public:
  explicit Tap(int planned) : planned_(planned) {
    std::printf("TAP version 13\n1..%d\n", planned);
    std::fflush(stdout);
  }
  // Returns ok, so that a test can stop early when a prerequisite failed.
  bool ok(bool ok, const std::string& desc) {
    ++n_;
    if (!ok) ++failed_;
    std::printf("%s %d %s\n", ok ? "ok" : "not ok", n_, desc.c_str());
    std::fflush(stdout);
    return ok;
  }
  void diag(const char* fmt, ...) __attribute__((format(printf, 2, 3))) {
    va_list ap;
    va_start(ap, fmt);
    std::fputs("# ", stdout);
    std::vprintf(fmt, ap);
    std::fputs("\n", stdout);
    std::fflush(stdout);
    va_end(ap);
  }
  int finish() {
    if (n_ != planned_) {
      diag("planned %d tests but ran %d", planned_, n_);
      return 1;
    }
    return failed_ ? 1 : 0;
  }

 private:
  int planned_, n_ = 0, failed_ = 0;
};

}  // namespace advee::rs485sim::vmtest
