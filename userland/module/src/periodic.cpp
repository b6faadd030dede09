// SPDX-License-Identifier: GPL-2.0
#include "advee/module/periodic.hpp"

#include <poll.h>
#include <sys/eventfd.h>
#include <sys/timerfd.h>
#include <unistd.h>

#include <cerrno>
#include <system_error>

#include "advee/throw_errno.hpp"

namespace advee::module {

PeriodicTimer::PeriodicTimer(std::chrono::nanoseconds period)
    : fd_(::timerfd_create(CLOCK_MONOTONIC, TFD_NONBLOCK | TFD_CLOEXEC)), period_(period) {
  if (!fd_) throw_errno("timerfd_create");
  if (period.count() <= 0) throw std::invalid_argument("timer period must be positive");
  itimerspec its{};
  its.it_interval.tv_sec = period.count() / 1'000'000'000;
  its.it_interval.tv_nsec = period.count() % 1'000'000'000;
  its.it_value = its.it_interval;
  if (::timerfd_settime(fd_.get(), 0, &its, nullptr) < 0) throw_errno("timerfd_settime");
}

std::uint64_t PeriodicTimer::consume() {
  std::uint64_t n = 0;
  if (::read(fd_.get(), &n, sizeof n) != sizeof n) {
    if (errno == EAGAIN) return 0;
    throw_errno("read timerfd");
  }
  return n;
}

Waker::Waker() : fd_(::eventfd(0, EFD_NONBLOCK | EFD_CLOEXEC)) {
  if (!fd_) throw_errno("eventfd");
}

void Waker::notify() {
  const std::uint64_t one = 1;
  // Cannot fail short of a counter overflow, which would still leave it readable.
  [[maybe_unused]] auto r = ::write(fd_.get(), &one, sizeof one);
}

bool Waker::consume() {
  std::uint64_t n = 0;
  return ::read(fd_.get(), &n, sizeof n) == sizeof n && n > 0;
}

PeriodicWait::Result PeriodicWait::next() {
  for (;;) {
    if (interrupted_) return Interrupted;
    pollfd fds[2] = {{waker_.fd(), POLLIN, 0}, {timer_.fd(), POLLIN, 0}};
    if (::poll(fds, 2, -1) < 0) {
      if (errno == EINTR) continue;
      throw_errno("poll");
    }
    if (fds[0].revents & POLLIN) {
      waker_.consume();
      interrupted_ = true;
      continue;
    }
    if ((fds[1].revents & POLLIN) && timer_.consume() > 0) return Tick;
  }
}

}  // namespace advee::module
