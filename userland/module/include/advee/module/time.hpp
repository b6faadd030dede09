// SPDX-License-Identifier: GPL-2.0
// The utime of the messages: CLOCK_REALTIME in microseconds, comparable
// between computers (the thesis's messaging_get_timestamp()).
#pragma once

#include <chrono>
#include <cstdint>

namespace advee::module {

inline std::int64_t utime_now() {
  return std::chrono::duration_cast<std::chrono::microseconds>(
             std::chrono::system_clock::now().time_since_epoch())
      .count();
}

}  // namespace advee::module
