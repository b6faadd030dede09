// SPDX-License-Identifier: GPL-2.0
// TimerSource: one-shot and periodic timers, cancellation (also from inside
// a callback), missed periods, exceptions, and fd() readiness, on the manual
// clock; MonotonicTimers against the kernel's clock.
#include <gtest/gtest.h>
#include <poll.h>

#include <stdexcept>
#include <string>
#include <vector>

#include "advee/module/timers.hpp"

using namespace advee::module;
using namespace std::chrono_literals;

namespace {

bool readable(const TimerSource& s) {
  pollfd p{s.fd(), POLLIN, 0};
  return ::poll(&p, 1, 0) == 1;
}

// What a loop does: dispatch while the fd says something is due.
void run_due(TimerSource& s) {
  while (readable(s)) s.dispatch();
}

TEST(ManualTimers, OneShotRunsOnceAtItsTime) {
  ManualTimers c;
  int runs = 0;
  Timer t = c.at(c.now() + 10ms, [&] { ++runs; });
  EXPECT_FALSE(readable(c));
  c.advance(9ms);
  EXPECT_FALSE(readable(c));
  c.advance(1ms);
  EXPECT_TRUE(readable(c));
  EXPECT_EQ(runs, 0);  // advance() only makes it due: the loop runs it
  run_due(c);
  EXPECT_EQ(runs, 1);
  c.advance(1h);
  run_due(c);
  EXPECT_EQ(runs, 1);
  EXPECT_EQ(c.pending(), 0u);
}

TEST(ManualTimers, PeriodicKeepsItsPhaseAndSkipsMissedPeriods) {
  ManualTimers c;
  std::vector<long> at;
  const auto t0 = c.now();
  Timer t = c.every(10ms, [&] {
    at.push_back(std::chrono::duration_cast<std::chrono::milliseconds>(c.now() - t0).count());
  });
  for (int i = 0; i < 25; ++i) {
    c.advance(1ms);
    run_due(c);
  }
  c.advance(47ms);  // 72 ms: the ones at 30..70 were missed, one run for them
  run_due(c);
  c.advance(8ms);  // 80 ms: on the original phase
  run_due(c);
  EXPECT_EQ(at, (std::vector<long>{10, 20, 72, 80}));
  EXPECT_THROW((void)c.every(0ms, [] {}), std::invalid_argument);
}

TEST(ManualTimers, DestroyingTheHandleCancels) {
  ManualTimers c;
  int runs = 0;
  {
    Timer t = c.every(1ms, [&] { ++runs; });
    Timer moved = std::move(t);
    EXPECT_FALSE(t);
    EXPECT_TRUE(moved);
  }
  EXPECT_EQ(c.pending(), 0u);
  c.advance(10ms);
  run_due(c);
  EXPECT_EQ(runs, 0);
}

TEST(ManualTimers, ACallbackMayCancelItselfAndOthersDueWithIt) {
  ManualTimers c;
  std::vector<std::string> ran;
  Timer a, b;
  a = c.every(5ms, [&] {
    ran.push_back("a");
    a.reset();
    b.reset();  // due at the same time, not yet run: does not run
  });
  b = c.at(c.now() + 5ms, [&] { ran.push_back("b"); });
  c.advance(20ms);
  run_due(c);
  EXPECT_EQ(ran, (std::vector<std::string>{"a"}));
  EXPECT_EQ(c.pending(), 0u);
}

TEST(ManualTimers, EarlierDeadlinesRunFirstAndNewTimersWaitForTheNextDispatch) {
  ManualTimers c;
  std::vector<int> ran;
  Timer later = c.at(c.now() + 3ms, [&] { ran.push_back(3); });
  Timer added;
  Timer sooner = c.at(c.now() + 1ms, [&] {
    ran.push_back(1);
    added = c.at(c.now(), [&] { ran.push_back(0); });  // due now: next dispatch
  });
  c.advance(3ms);
  c.dispatch();
  EXPECT_EQ(ran, (std::vector<int>{1, 3}));
  EXPECT_TRUE(readable(c));
  c.dispatch();
  EXPECT_EQ(ran, (std::vector<int>{1, 3, 0}));
}

TEST(ManualTimers, AnExceptionLeavesTheTimersConsistent) {
  ManualTimers c;
  int periodic = 0;
  Timer boom = c.at(c.now() + 1ms, [] { throw std::runtime_error("boom"); });
  Timer tick = c.every(2ms, [&] { ++periodic; });
  c.advance(2ms);
  EXPECT_THROW(c.dispatch(), std::runtime_error);
  EXPECT_EQ(c.pending(), 1u);  // the one-shot is gone, the periodic one stays
  EXPECT_TRUE(readable(c));    // and is still due
  run_due(c);
  EXPECT_EQ(periodic, 1);
  c.advance(2ms);
  run_due(c);
  EXPECT_EQ(periodic, 2);
}

TEST(MonotonicTimers, FiresOnTheKernelClock) {
  MonotonicTimers c;
  int runs = 0;
  const auto start = c.now();
  Timer t = c.at(start + 2ms, [&] { ++runs; });
  pollfd p{c.fd(), POLLIN, 0};
  ASSERT_EQ(::poll(&p, 1, 10000), 1);  // a deadline only a failure reaches
  EXPECT_GE(c.now() - start, 2ms);
  c.dispatch();
  EXPECT_EQ(runs, 1);
  Timer never = c.at(c.now() + 1h, [&] { ++runs; });
  EXPECT_FALSE(readable(c));
  never.reset();
  c.dispatch();  // a cancelled deadline: nothing to run
  EXPECT_EQ(runs, 1);
}

}  // namespace
