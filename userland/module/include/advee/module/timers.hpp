// SPDX-License-Identifier: GPL-2.0
// The loop's time: now() and timers that run on the loop thread. The Module
// loop and the supervisor read time only through a TimerSource, so their
// unit tests drive them with ManualTimers (time moves only when the test
// says so: no wall-clock waits, nothing that load can delay) and production
// uses MonotonicTimers (CLOCK_MONOTONIC, one timerfd). The shape is that of
// sd-event's sd_event_now() + sd_event_add_time(): a loop integrates a
// source by polling fd() and calling dispatch() when it is readable.
// Not thread-safe: everything runs on the loop thread.
#pragma once

#include <chrono>
#include <cstdint>
#include <functional>
#include <map>
#include <optional>

#include "advee/unique_fd.hpp"

namespace advee::module {

using SteadyClock = std::chrono::steady_clock;  // CLOCK_MONOTONIC on Linux
using TimePoint = SteadyClock::time_point;
using Duration = std::chrono::nanoseconds;

class TimerSource;

// One scheduled timer; destroying it (or reset()) cancels it. It must not
// outlive its source.
class Timer {
 public:
  Timer() = default;
  Timer(Timer&& o) noexcept : source_(o.source_), id_(o.id_) { o.source_ = nullptr; }
  Timer& operator=(Timer&& o) noexcept;
  Timer(const Timer&) = delete;
  Timer& operator=(const Timer&) = delete;
  ~Timer() { reset(); }
  void reset();
  explicit operator bool() const { return source_ != nullptr; }

 private:
  friend class TimerSource;
  Timer(TimerSource* s, std::uint64_t id) : source_(s), id_(id) {}
  TimerSource* source_ = nullptr;
  std::uint64_t id_ = 0;
};

class TimerSource {
 public:
  TimerSource() = default;
  TimerSource(const TimerSource&) = delete;
  TimerSource& operator=(const TimerSource&) = delete;
  virtual ~TimerSource() = default;

  virtual TimePoint now() const = 0;
  // fn runs once, on the loop, at or after `when`.
  [[nodiscard]] Timer at(TimePoint when, std::function<void()> fn);
  // fn runs every `period` (> 0, else std::invalid_argument), the first time
  // one period from now. A loop that fell behind runs fn once for all the
  // periods it missed (as one read of a timerfd's expiration count would)
  // and keeps the phase.
  [[nodiscard]] Timer every(Duration period, std::function<void()> fn);

  // Readable while a timer is due.
  virtual int fd() const = 0;
  // Runs the timers due at now() (those a timer schedules for now or earlier
  // run on the next dispatch) and rearms fd(). A callback's exception
  // propagates after its timer was rescheduled or removed.
  void dispatch();
  // Number of scheduled timers (tests).
  std::size_t pending() const { return timers_.size(); }

 protected:
  // Make fd() readable at `earliest` (nullopt: no timer) and not before.
  virtual void arm(std::optional<TimePoint> earliest) = 0;
  // Called at the start of dispatch(): fd() stops being readable.
  virtual void clear() = 0;

 private:
  friend class Timer;
  struct Entry {
    TimePoint when;
    Duration period;  // zero: once
    std::function<void()> fn;
  };
  Timer add(TimePoint when, Duration period, std::function<void()> fn);
  void cancel(std::uint64_t id);
  void rearm();

  std::map<std::uint64_t, Entry> timers_;
  std::uint64_t next_id_ = 1;
};

// Production: steady_clock and a CLOCK_MONOTONIC timerfd armed at the
// earliest deadline. Throws std::system_error.
class MonotonicTimers final : public TimerSource {
 public:
  MonotonicTimers();
  TimePoint now() const override { return SteadyClock::now(); }
  int fd() const override { return fd_.get(); }

 protected:
  void arm(std::optional<TimePoint> earliest) override;
  void clear() override;

 private:
  UniqueFd fd_;
};

// Tests and simulations: time moves only by advance(). fd() (an eventfd) is
// readable while a timer is due, so a loop polling it runs the timers
// itself, on its own thread, exactly as with MonotonicTimers. A loop that
// waits without a deadline (Module::run()) wakes for a timer only if
// advance() made it due before: tests step with advance() + run_once(0ms).
class ManualTimers final : public TimerSource {
 public:
  ManualTimers();
  TimePoint now() const override { return now_; }
  int fd() const override { return fd_.get(); }
  void advance(Duration d);

 protected:
  void arm(std::optional<TimePoint> earliest) override;
  void clear() override;

 private:
  void signal_if_due();
  UniqueFd fd_;
  TimePoint now_{std::chrono::seconds(1000)};
  std::optional<TimePoint> earliest_;
};

}  // namespace advee::module
