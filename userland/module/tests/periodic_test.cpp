// SPDX-License-Identifier: GPL-2.0
#include <gtest/gtest.h>

#include <chrono>
#include <thread>

#include "advee/module/periodic.hpp"

using namespace advee::module;
using namespace std::chrono_literals;

TEST(Periodic, TimerCountsExpirations) {
  PeriodicTimer t(10ms);
  EXPECT_EQ(t.consume(), 0u);  // first expiry is one period away
  std::this_thread::sleep_for(55ms);
  EXPECT_GE(t.consume(), 4u);
  EXPECT_EQ(t.consume(), 0u);  // consumed
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
  PeriodicWait wait(5ms);
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
  std::thread poller([&] {
    while (wait.next() == PeriodicWait::Tick) ++ticks;
  });
  std::this_thread::sleep_for(20ms);
  wait.interrupt();
  poller.join();
  EXPECT_EQ(ticks, 0);
}
