// SPDX-License-Identifier: GPL-2.0
// Tests of modules on ManualTimers: run `d` of module time in steps, each
// followed by loop passes that do not wait, so that what became ready is
// handled (memq delivers on the pass after a publish, a command acts on the
// pass after its delivery). No wall-clock time passes.
#pragma once

#include <chrono>

#include "advee/module/module.hpp"
#include "advee/module/timers.hpp"

namespace advee::module {

inline void run_manual(Module& m, ManualTimers& clock, Duration d,
                       Duration step = std::chrono::milliseconds(1), int passes = 4) {
  for (Duration t{}; t < d; t += step) {
    clock.advance(step);
    for (int i = 0; i < passes && m.run_once(std::chrono::milliseconds(0)); ++i) {
    }
  }
}

}  // namespace advee::module
