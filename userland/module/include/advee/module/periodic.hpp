// SPDX-License-Identifier: GPL-2.0
// Periodic timing and interruptible waits on file descriptors (replacing the
// seed's pipe trick): a timerfd ticks at a fixed period, an eventfd lets any
// thread interrupt a wait at once, and both are plain fds an event loop polls.
#pragma once

#include <chrono>
#include <cstdint>

#include "advee/unique_fd.hpp"

namespace advee::module {

// CLOCK_MONOTONIC timerfd firing every `period` (first expiry one period
// after construction). Throws std::system_error.
class PeriodicTimer {
 public:
  explicit PeriodicTimer(std::chrono::nanoseconds period);
  int fd() const { return fd_.get(); }
  // Expirations since the last call (0 if none; never blocks).
  std::uint64_t consume();
  std::chrono::nanoseconds period() const { return period_; }

 private:
  UniqueFd fd_;
  std::chrono::nanoseconds period_;
};

// eventfd: notify() from any thread makes fd() readable until consume().
class Waker {
 public:
  Waker();
  int fd() const { return fd_.get(); }
  void notify();  // async-signal-safe
  bool consume();  // true if notify() was called since the last consume()

 private:
  UniqueFd fd_;
};

// A polling thread's loop: `while (wait.next() == PeriodicWait::Tick) poll();`
// ends as soon as another thread calls interrupt().
class PeriodicWait {
 public:
  enum Result { Tick, Interrupted };
  explicit PeriodicWait(std::chrono::nanoseconds period) : timer_(period) {}
  // Blocks until the next tick or an interrupt; an interrupt is sticky (every
  // later next() returns Interrupted at once).
  Result next();
  void interrupt() { waker_.notify(); }

 private:
  PeriodicTimer timer_;
  Waker waker_;
  bool interrupted_ = false;
};

}  // namespace advee::module
