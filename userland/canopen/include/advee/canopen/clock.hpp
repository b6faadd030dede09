// SPDX-License-Identifier: GPL-2.0
// The engine reads time only through an injected function, so unit tests can
// drive every timeout deterministically and the event loop supplies the
// monotonic clock in production.
#pragma once

#include <chrono>
#include <functional>

namespace advee::canopen {

using SteadyClock = std::chrono::steady_clock;
using TimePoint = SteadyClock::time_point;
using Duration = SteadyClock::duration;
using NowFn = std::function<TimePoint()>;

inline NowFn system_monotonic_clock() {
  return [] { return SteadyClock::now(); };
}

// A clock that moves only when told to (tests, simulations).
class ManualClock {
 public:
  TimePoint now() const { return now_; }
  void advance(Duration d) { now_ += d; }
  NowFn fn() {
    return [this] { return now_; };
  }

 private:
  TimePoint now_{std::chrono::seconds(1000)};
};

}  // namespace advee::canopen
