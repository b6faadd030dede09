// SPDX-License-Identifier: GPL-2.0
// Restart back-off of one supervised module. The first restart after a run
// that lasted at least `stable` is immediate (a module that was fine and died
// once comes back at once); every further restart without such a run waits
// initial, initial*factor, initial*factor^2, ... capped at `max`.
#pragma once

#include <chrono>

namespace advee::watchdog {

using Millis = std::chrono::milliseconds;

struct BackoffConfig {
  Millis initial{500};
  Millis max{30'000};
  double factor = 2.0;
  Millis stable{10'000};
};

class Backoff {
 public:
  explicit Backoff(BackoffConfig cfg) : cfg_(cfg) {}
  // The process exited after running `ran_for`: the delay before the next start.
  Millis on_exit(Millis ran_for);
  // Quick failures in a row (0 after a stable run or a reset).
  int failures() const { return failures_; }
  void reset() { failures_ = 0; }
  const BackoffConfig& config() const { return cfg_; }

 private:
  BackoffConfig cfg_;
  int failures_ = 0;
};

}  // namespace advee::watchdog
