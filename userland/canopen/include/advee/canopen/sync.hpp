// SPDX-License-Identifier: GPL-2.0
// SYNC producer with the optional counter of object 0x1019: overflow 0 means
// no counter (DLC 0); 2..240 gives a 1-byte counter that starts at 1 and wraps
// to 1 after the overflow value (canopen-notes.md §3.8).
#pragma once

#include <cstdint>
#include <functional>
#include <optional>

#include "advee/canopen/clock.hpp"
#include "advee/canopen/frame.hpp"

namespace advee::canopen {

class SyncProducer {
 public:
  SyncProducer(FrameSender send, NowFn now);

  // Throws std::invalid_argument for overflow 1 or > 240 or a zero period.
  void start(Duration period, std::uint8_t counter_overflow = 0);
  void stop();
  bool running() const { return period_.count() != 0; }
  void poll();
  std::optional<TimePoint> deadline() const;
  // Called after each SYNC is sent, with the counter it carried (0 without counter).
  void on_sync(std::function<void(std::uint8_t)> cb) { on_sync_ = std::move(cb); }

 private:
  FrameSender send_;
  NowFn now_;
  Duration period_{};
  std::uint8_t overflow_ = 0;
  std::uint8_t counter_ = 1;
  TimePoint next_{};
  std::function<void(std::uint8_t)> on_sync_;
};

// TIME object (0x100): TIME_OF_DAY = ms after midnight (28 bits) + days since
// 1984-01-01 (16 bits).
CanFrame time_of_day_frame(std::chrono::system_clock::time_point t);
std::optional<std::chrono::system_clock::time_point> decode_time_of_day(const CanFrame& f);

using WallClockFn = std::function<std::chrono::system_clock::time_point()>;

// Periodic TIME producer. The period runs on the engine's monotonic clock;
// the content comes from the wall clock (injected too).
class TimeProducer {
 public:
  TimeProducer(FrameSender send, NowFn now, WallClockFn wall);
  void start(Duration period);  // sends one at once; zero or negative stops
  void stop() { period_ = Duration::zero(); }
  void poll();
  std::optional<TimePoint> deadline() const;

 private:
  FrameSender send_;
  NowFn now_;
  WallClockFn wall_;
  Duration period_{};
  TimePoint next_{};
};

}  // namespace advee::canopen
