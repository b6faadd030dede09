// SPDX-License-Identifier: GPL-2.0
#include "advee/watchdog/backoff.hpp"

#include <algorithm>
#include <cmath>

namespace advee::watchdog {

Millis Backoff::on_exit(Millis ran_for) {
  if (ran_for >= cfg_.stable) failures_ = 0;
  const int n = failures_++;
  if (n == 0) return Millis(0);
  // initial * factor^(n-1), computed in double and capped before the cast.
  const double ms = static_cast<double>(cfg_.initial.count()) * std::pow(cfg_.factor, n - 1);
  const double capped = std::min(ms, static_cast<double>(cfg_.max.count()));
  return Millis(static_cast<Millis::rep>(capped));
}

}  // namespace advee::watchdog
