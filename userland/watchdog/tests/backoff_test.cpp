// SPDX-License-Identifier: GPL-2.0
#include <gtest/gtest.h>

#include <vector>

#include "advee/watchdog/backoff.hpp"

using namespace advee::watchdog;
using namespace std::chrono_literals;

TEST(Backoff, CrashLoopDoublesUpToTheCap) {
  Backoff b({500ms, 5000ms, 2.0, 10'000ms});
  std::vector<long> got;
  for (int i = 0; i < 8; ++i) got.push_back(b.on_exit(100ms).count());
  EXPECT_EQ(got, (std::vector<long>{0, 500, 1000, 2000, 4000, 5000, 5000, 5000}));
  EXPECT_EQ(b.failures(), 8);
}

TEST(Backoff, AStableRunResetsTheSchedule) {
  Backoff b({500ms, 30'000ms, 2.0, 10'000ms});
  b.on_exit(1s);
  b.on_exit(1s);
  EXPECT_EQ(b.on_exit(1s), 1000ms);
  EXPECT_EQ(b.on_exit(10s), 0ms);  // ran long enough: fine again, immediate restart
  EXPECT_EQ(b.on_exit(1s), 500ms);
}

TEST(Backoff, ResetMakesTheNextStartImmediate) {
  Backoff b({200ms, 1000ms, 3.0, 10'000ms});
  b.on_exit(0ms);
  EXPECT_EQ(b.on_exit(0ms), 200ms);
  EXPECT_EQ(b.on_exit(0ms), 600ms);
  EXPECT_EQ(b.on_exit(0ms), 1000ms);  // 1800 capped
  b.reset();
  EXPECT_EQ(b.on_exit(0ms), 0ms);
}

TEST(Backoff, HugeExponentsStayAtTheCap) {
  Backoff b({500ms, 60'000ms, 10.0, 10'000ms});
  Millis last{};
  for (int i = 0; i < 400; ++i) last = b.on_exit(0ms);
  EXPECT_EQ(last, 60'000ms);
}
