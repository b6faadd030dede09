// SPDX-License-Identifier: GPL-2.0
#include "advee/canopen/event_loop.hpp"

#include <sys/epoll.h>
#include <sys/eventfd.h>
#include <sys/timerfd.h>

#include <cerrno>
#include <system_error>

#include "advee/throw_errno.hpp"

namespace advee::canopen {

namespace {

timespec to_timespec(TimePoint t) {
  const auto ns = std::chrono::duration_cast<std::chrono::nanoseconds>(t.time_since_epoch()).count();
  timespec ts{};
  if (ns <= 0) {
    ts.tv_nsec = 1;  // zero would disarm the timer
    return ts;
  }
  ts.tv_sec = ns / 1000000000;
  ts.tv_nsec = ns % 1000000000;
  return ts;
}
}  // namespace

EventLoop::EventLoop()
    : epoll_(::epoll_create1(EPOLL_CLOEXEC)),
      timer_(::timerfd_create(CLOCK_MONOTONIC, TFD_NONBLOCK | TFD_CLOEXEC)),
      wake_(::eventfd(0, EFD_NONBLOCK | EFD_CLOEXEC)) {
  if (!epoll_) throw_errno("epoll_create1");
  if (!timer_) throw_errno("timerfd_create");
  if (!wake_) throw_errno("eventfd");
  add_fd(timer_.get(), EPOLLIN, [this](std::uint32_t) {
    std::uint64_t expirations;
    (void)!::read(timer_.get(), &expirations, sizeof expirations);
    armed_.reset();  // expired: the next arm_timer() must program it again
  });
  add_fd(wake_.get(), EPOLLIN, [this](std::uint32_t) {
    std::uint64_t n;
    (void)!::read(wake_.get(), &n, sizeof n);
    drain_posted();
  });
}

void EventLoop::add_fd(int fd, std::uint32_t events, FdHandler h) {
  epoll_event ev{};
  ev.events = events;
  ev.data.fd = fd;
  if (::epoll_ctl(epoll_.get(), EPOLL_CTL_ADD, fd, &ev) < 0) throw_errno("epoll_ctl(ADD)");
  handlers_[fd] = std::move(h);
}

void EventLoop::modify_fd(int fd, std::uint32_t events) {
  epoll_event ev{};
  ev.events = events;
  ev.data.fd = fd;
  if (::epoll_ctl(epoll_.get(), EPOLL_CTL_MOD, fd, &ev) < 0) throw_errno("epoll_ctl(MOD)");
}

void EventLoop::remove_fd(int fd) {
  ::epoll_ctl(epoll_.get(), EPOLL_CTL_DEL, fd, nullptr);
  handlers_.erase(fd);
}

void EventLoop::add_timer_source(DeadlineFn deadline, std::function<void()> poll) {
  timers_.push_back({std::move(deadline), std::move(poll)});
}

void EventLoop::post(std::function<void()> fn) {
  {
    std::lock_guard lock(mutex_);
    posted_.push_back(std::move(fn));
  }
  const std::uint64_t one = 1;
  (void)!::write(wake_.get(), &one, sizeof one);
}

void EventLoop::stop() {
  post([this] { stopped_ = true; });
}

void EventLoop::drain_posted() {
  std::vector<std::function<void()>> work;
  {
    std::lock_guard lock(mutex_);
    work.swap(posted_);
  }
  for (auto& fn : work) fn();
}

void EventLoop::arm_timer() {
  std::optional<TimePoint> next;
  for (auto& t : timers_) {
    auto d = t.deadline();
    if (d && (!next || *d < *next)) next = d;
  }
  // Only move the timer earlier: a later or vanished deadline leaves the armed
  // one, which then costs one spurious wake-up instead of a syscall on every
  // request (an SDO stream moves its deadline later with each frame).
  if (armed_ && (!next || *armed_ <= *next)) return;
  if (!next) return;
  armed_ = next;
  itimerspec spec{};
  spec.it_value = to_timespec(*next);
  if (::timerfd_settime(timer_.get(), TFD_TIMER_ABSTIME, &spec, nullptr) < 0)
    throw_errno("timerfd_settime");
}

bool EventLoop::run_once(std::optional<Duration> max_wait) {
  if (stopped_) return false;
  arm_timer();
  epoll_event events[32];
  const int timeout_ms =
      max_wait ? static_cast<int>(std::chrono::duration_cast<std::chrono::milliseconds>(*max_wait).count()) : -1;
  const int n = ::epoll_wait(epoll_.get(), events, 32, timeout_ms);
  if (n < 0 && errno != EINTR) throw_errno("epoll_wait");
  for (int i = 0; i < n; ++i) {
    auto it = handlers_.find(events[i].data.fd);
    if (it != handlers_.end()) {
      auto h = it->second;  // the handler may remove itself
      h(events[i].events);
    }
  }
  for (auto& t : timers_) t.poll();
  return !stopped_;
}

void EventLoop::run() {
  while (run_once()) {
  }
}

}  // namespace advee::canopen
