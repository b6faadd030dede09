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

// When a periodic producer (SYNC, heartbeat, TIME) that was due at `due` and
// sent at `now` is next due. It keeps the grid (due + period), so wake-up
// jitter does not add up to a drifting period, unless the send was more than
// half a period late: then the cycle re-phases to now + period. So no two
// messages go out less than half a period apart, and periods missed in a
// stall are skipped, never sent in a burst.
inline TimePoint next_period(TimePoint due, TimePoint now, Duration period) {
  if (now - due > period / 2) return now + period;
  return due + period;
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
