// SPDX-License-Identifier: GPL-2.0
#include "advee/canopen/motion_watchdog.hpp"

namespace advee::canopen {

MotionWatchdog::MotionWatchdog(Master& master, Duration timeout, std::function<void()> on_expire)
    : master_(master), timeout_(timeout), on_expire_(std::move(on_expire)), service_(master_.attach(*this)) {}

void MotionWatchdog::feed() {
  last_ = master_.now();
  expired_ = false;
}

void MotionWatchdog::poll() {
  if (!last_ || expired_ || master_.now() - *last_ < timeout_) return;
  expired_ = true;
  if (on_expire_) on_expire_();
}

std::optional<TimePoint> MotionWatchdog::deadline() const {
  if (!last_ || expired_) return std::nullopt;
  return *last_ + timeout_;
}

}  // namespace advee::canopen
