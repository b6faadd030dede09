// SPDX-License-Identifier: GPL-2.0
// The periodic producers (SYNC, heartbeat, TIME) after a stall of the loop,
// and the master's own heartbeat (boot-up first, its real NMT state), with a
// manual clock.
#include <gtest/gtest.h>

#include <algorithm>

#include "advee/canopen/master.hpp"

namespace advee::canopen {
namespace {

using namespace std::chrono_literals;

// Records when each frame went out.
struct Recorder {
  ManualClock clock;
  const TimePoint start = clock.now();
  std::vector<Duration> at;
  std::vector<CanFrame> frames;
  FrameSender sender() {
    return [this](const CanFrame& f) {
      at.push_back(clock.now() - start);
      frames.push_back(f);
    };
  }
  // Polls every millisecond up to `total`, except in [stall_from, stall_to):
  // the loop did not run then.
  template <typename Poll>
  void run(Poll poll, Duration total, Duration stall_from, Duration stall_to) {
    while (clock.now() - start < total) {
      clock.advance(1ms);
      const Duration t = clock.now() - start;
      if (t >= stall_from && t < stall_to) continue;
      poll();
    }
  }
  Duration min_gap() const {
    Duration m = Duration::max();
    for (std::size_t i = 1; i < at.size(); ++i) m = std::min(m, at[i] - at[i - 1]);
    return m;
  }
  std::string times() const {
    std::string s;
    for (auto d : at) s += std::to_string(std::chrono::duration_cast<std::chrono::milliseconds>(d).count()) + " ";
    return s;
  }
};

TEST(PeriodicTest, SyncAfterAStallOfOnePeriodIsNotFollowedByAShortGap) {
  Recorder r;
  SyncProducer sync(r.sender(), r.clock.fn());
  sync.start(10ms);
  // Due at 10 ms; the loop stalls from 4 to 16 ms, so that SYNC goes out 6 ms late.
  r.run([&] { sync.poll(); }, 100ms, 4ms, 16ms);
  ASSERT_GE(r.at.size(), 2u);
  EXPECT_EQ(r.at[0], 16ms);
  EXPECT_GE(r.min_gap(), 5ms) << "SYNC at (ms): " << r.times();
  EXPECT_EQ(r.at[1], 26ms) << "re-phased to a full period after the late one: " << r.times();
}

TEST(PeriodicTest, SyncKeepsItsGridUnderSmallWakeUpDelays) {
  Recorder r;
  SyncProducer sync(r.sender(), r.clock.fn());
  sync.start(10ms);
  // Every wake-up 3 ms after the deadline (timer slack): the period must not
  // drift to 13 ms.
  while (r.clock.now() - r.start < 1s) {
    r.clock.advance(*sync.deadline() - r.clock.now() + 3ms);
    sync.poll();
  }
  EXPECT_EQ(r.at.size(), 100u) << r.times();
  EXPECT_EQ(r.at.back(), 1003ms);
}

TEST(PeriodicTest, HeartbeatAfterAStallOfOnePeriodIsNotFollowedByAShortGap) {
  Recorder r;
  HeartbeatProducer hb(0x7F, r.sender(), r.clock.fn());
  hb.set_period(100ms);  // one at once (0 ms), then due at 100 ms
  r.run([&] { hb.poll(); }, 500ms, 40ms, 160ms);
  ASSERT_GE(r.at.size(), 3u);
  EXPECT_EQ(r.at[1], 160ms);
  EXPECT_GE(r.min_gap(), 50ms) << "heartbeat at (ms): " << r.times();
}

TEST(PeriodicTest, TimeAfterAStallOfOnePeriodIsNotFollowedByAShortGap) {
  Recorder r;
  TimeProducer time(r.sender(), r.clock.fn(), [] { return std::chrono::system_clock::time_point{}; });
  time.start(1s);  // one at once, then due at 1 s
  r.run([&] { time.poll(); }, 4s, 400ms, 1600ms);
  ASSERT_GE(r.at.size(), 3u);
  EXPECT_EQ(r.at[1], 1600ms);
  EXPECT_GE(r.min_gap(), 500ms) << "TIME at (ms): " << r.times();
}

TEST(PeriodicTest, MasterHeartbeatStartsWithBootUpAndReportsPreOperational) {
  Recorder r;
  Master m(MasterConfig{0x7F, 100ms, 100ms}, r.sender(), r.clock.fn());
  ASSERT_GE(r.frames.size(), 2u);
  EXPECT_EQ(to_string(r.frames[0]), "77F#00") << "boot-up before the first heartbeat";
  EXPECT_EQ(to_string(r.frames[1]), "77F#7F") << "pre-operational until the owner starts it";
}

TEST(PeriodicTest, MasterHeartbeatCarriesItsNmtState) {
  Recorder r;
  Master m(MasterConfig{0x7F, 100ms, 100ms}, r.sender(), r.clock.fn());
  EXPECT_EQ(m.nmt_state(), NmtState::kPreOperational);
  m.set_nmt_state(NmtState::kOperational);
  r.run([&] { m.poll(); }, 100ms, 0ms, 0ms);
  ASSERT_EQ(r.frames.size(), 3u);
  EXPECT_EQ(to_string(r.frames[2]), "77F#05");
  m.set_nmt_state(NmtState::kStopped);
  r.run([&] { m.poll(); }, 200ms, 0ms, 0ms);
  ASSERT_EQ(r.frames.size(), 4u);
  EXPECT_EQ(to_string(r.frames[3]), "77F#04");
  // Off and on again: no second boot-up (the master did not reset).
  m.set_heartbeat_period(0ms);
  m.set_heartbeat_period(100ms);
  ASSERT_EQ(r.frames.size(), 5u);
  EXPECT_EQ(to_string(r.frames[4]), "77F#04");
}

TEST(PeriodicTest, MasterWithoutHeartbeatStaysSilent) {
  Recorder r;
  Master m(MasterConfig{0x7F, 100ms, {}}, r.sender(), r.clock.fn());
  r.run([&] { m.poll(); }, 1s, 0ms, 0ms);
  EXPECT_TRUE(r.frames.empty()) << "a tool (advee-canopenctl) is no node on the network";
}

}  // namespace
}  // namespace advee::canopen
