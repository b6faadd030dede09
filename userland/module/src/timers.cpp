// SPDX-License-Identifier: GPL-2.0
#include "advee/module/timers.hpp"

#include <sys/eventfd.h>
#include <sys/timerfd.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <stdexcept>
#include <system_error>
#include <utility>
#include <vector>

#include "advee/throw_errno.hpp"

namespace advee::module {

Timer& Timer::operator=(Timer&& o) noexcept {
  if (this != &o) {
    reset();
    source_ = std::exchange(o.source_, nullptr);
    id_ = o.id_;
  }
  return *this;
}

void Timer::reset() {
  if (source_) std::exchange(source_, nullptr)->cancel(id_);
}

Timer TimerSource::at(TimePoint when, std::function<void()> fn) {
  return add(when, Duration::zero(), std::move(fn));
}

Timer TimerSource::every(Duration period, std::function<void()> fn) {
  if (period <= Duration::zero()) throw std::invalid_argument("timer period must be positive");
  return add(now() + period, period, std::move(fn));
}

Timer TimerSource::add(TimePoint when, Duration period, std::function<void()> fn) {
  const std::uint64_t id = next_id_++;
  timers_.emplace(id, Entry{when, period, std::move(fn)});
  rearm();
  return Timer(this, id);
}

// No rearm: a cancelled earliest deadline costs one wake-up that finds
// nothing due, not a system call on every cancel (and cancel runs in
// destructors, which must not throw).
void TimerSource::cancel(std::uint64_t id) { timers_.erase(id); }

void TimerSource::rearm() {
  std::optional<TimePoint> earliest;
  for (const auto& [id, e] : timers_)
    if (!earliest || e.when < *earliest) earliest = e.when;
  arm(earliest);
}

void TimerSource::dispatch() {
  clear();
  const TimePoint t = now();
  std::vector<std::pair<TimePoint, std::uint64_t>> due;
  for (const auto& [id, e] : timers_)
    if (e.when <= t) due.emplace_back(e.when, id);
  std::sort(due.begin(), due.end());
  for (const auto& [when, id] : due) {
    auto it = timers_.find(id);
    if (it == timers_.end()) continue;  // cancelled by an earlier callback
    Entry& e = it->second;
    std::function<void()> fn;
    if (e.period == Duration::zero()) {
      fn = std::move(e.fn);
      timers_.erase(it);
    } else {
      e.when += ((t - e.when) / e.period + 1) * e.period;  // the next one after t
      fn = e.fn;  // a copy: the callback may cancel its own timer
    }
    try {
      fn();
    } catch (...) {
      rearm();
      throw;
    }
  }
  rearm();
}

MonotonicTimers::MonotonicTimers()
    : fd_(::timerfd_create(CLOCK_MONOTONIC, TFD_NONBLOCK | TFD_CLOEXEC)) {
  if (!fd_) throw_errno("timerfd_create");
}

void MonotonicTimers::arm(std::optional<TimePoint> earliest) {
  itimerspec spec{};  // zero: disarmed
  if (earliest) {
    const auto ns =
        std::chrono::duration_cast<std::chrono::nanoseconds>(earliest->time_since_epoch()).count();
    spec.it_value.tv_sec = ns > 0 ? ns / 1'000'000'000 : 0;
    spec.it_value.tv_nsec = ns > 0 ? ns % 1'000'000'000 : 1;  // zero would disarm it
  }
  if (::timerfd_settime(fd_.get(), TFD_TIMER_ABSTIME, &spec, nullptr) < 0)
    throw_errno("timerfd_settime");
}

void MonotonicTimers::clear() {
  std::uint64_t n;
  [[maybe_unused]] auto r = ::read(fd_.get(), &n, sizeof n);  // EAGAIN: nothing expired
}

ManualTimers::ManualTimers() : fd_(::eventfd(0, EFD_NONBLOCK | EFD_CLOEXEC)) {
  if (!fd_) throw_errno("eventfd");
}

void ManualTimers::advance(Duration d) {
  now_ += d;
  signal_if_due();
}

void ManualTimers::arm(std::optional<TimePoint> earliest) {
  earliest_ = earliest;
  signal_if_due();
}

void ManualTimers::clear() {
  std::uint64_t n;
  [[maybe_unused]] auto r = ::read(fd_.get(), &n, sizeof n);
}

void ManualTimers::signal_if_due() {
  if (!earliest_ || *earliest_ > now_) return;
  const std::uint64_t one = 1;
  [[maybe_unused]] auto r = ::write(fd_.get(), &one, sizeof one);
}

}  // namespace advee::module
