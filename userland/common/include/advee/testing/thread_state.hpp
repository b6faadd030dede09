// SPDX-License-Identifier: GPL-2.0
// For tests that must act while another thread is blocked (in poll(), on a
// mutex): wait for that condition instead of sleeping and hoping.
#pragma once

#include <sys/syscall.h>
#include <unistd.h>

#include <chrono>
#include <fstream>
#include <iterator>
#include <string>
#include <thread>

namespace advee::testing {

inline pid_t current_tid() { return static_cast<pid_t>(::syscall(SYS_gettid)); }

// The scheduler state of thread `tid` of this process ('S': asleep in a
// system call, 'R': running; '?' when it cannot be read).
inline char thread_state(pid_t tid) {
  std::ifstream f("/proc/self/task/" + std::to_string(tid) + "/stat");
  const std::string stat((std::istreambuf_iterator<char>(f)), std::istreambuf_iterator<char>());
  const auto paren = stat.rfind(')');  // the name in parentheses may hold anything
  return paren == std::string::npos || paren + 2 >= stat.size() ? '?' : stat[paren + 2];
}

// True once thread `tid` sleeps; false after `limit` (only a failure waits that long).
inline bool wait_until_asleep(pid_t tid, std::chrono::milliseconds limit = std::chrono::seconds(10)) {
  const auto end = std::chrono::steady_clock::now() + limit;
  while (thread_state(tid) != 'S') {
    if (std::chrono::steady_clock::now() >= end) return false;
    std::this_thread::yield();
  }
  return true;
}

}  // namespace advee::testing
