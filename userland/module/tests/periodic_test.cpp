// SPDX-License-Identifier: GPL-2.0
// The fd wrappers on the kernel's own clock. No test sleeps for a time: each
// waits for a condition (bounded by a deadline that only a failure reaches),
// and only lower bounds of elapsed time are relied on, which load cannot break.
#include <gtest/gtest.h>
#include <poll.h>

#include <atomic>
#include <chrono>
#include <thread>

#include "advee/module/periodic.hpp"
#include "advee/testing/thread_state.hpp"

using namespace advee::module;
using namespace std::chrono_literals;

TEST(Periodic, TimerCountsExpirations) {
  PeriodicTimer never(std::chrono::hours(1));
  EXPECT_EQ(never.consume(), 0u);  // first expiry one period away; never blocks
  PeriodicTimer t(1ms);
  std::uint64_t total = 0;
  const auto deadline = std::chrono::steady_clock::now() + 10s;
  while (total < 5 && std::chrono::steady_clock::now() < deadline) {
    pollfd p{t.fd(), POLLIN, 0};
    ASSERT_GE(::poll(&p, 1, 1000), 0);
    total += t.consume();
  }
  EXPECT_GE(total, 5u);
  EXPECT_THROW(PeriodicTimer(0ms), std::invalid_argument);
}

TEST(Periodic, WakerIsLevelTriggeredUntilConsumed) {
  Waker w;
  EXPECT_FALSE(w.consume());
  w.notify();
  w.notify();
  EXPECT_TRUE(w.consume());
  EXPECT_FALSE(w.consume());
}

TEST(Periodic, WaitTicksThenAnInterruptEndsIt) {
  PeriodicWait wait(1ms);
  EXPECT_EQ(wait.next(), PeriodicWait::Tick);
  EXPECT_EQ(wait.next(), PeriodicWait::Tick);
  wait.interrupt();
  EXPECT_EQ(wait.next(), PeriodicWait::Interrupted);
  EXPECT_EQ(wait.next(), PeriodicWait::Interrupted);  // sticky
}

TEST(Periodic, InterruptFromAnotherThreadEndsALongWait) {
  // A one-hour period: only the interrupt can end next().
  PeriodicWait wait(std::chrono::hours(1));
  int ticks = 0;
  std::atomic<pid_t> tid{0};
  std::thread poller([&] {
    tid = advee::testing::current_tid();
    while (wait.next() == PeriodicWait::Tick) ++ticks;
  });
  // Interrupt it while it sleeps in poll() (an interrupt before would end it
  // too, being sticky, but would not test the wake-up).
  while (tid == 0) std::this_thread::yield();
  EXPECT_TRUE(advee::testing::wait_until_asleep(tid));
  wait.interrupt();
  poller.join();
  EXPECT_EQ(ticks, 0);
}
