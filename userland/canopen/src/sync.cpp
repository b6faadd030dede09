// SPDX-License-Identifier: GPL-2.0
#include "advee/canopen/sync.hpp"

#include <stdexcept>

#include "advee/byte_order.hpp"

namespace advee::canopen {

SyncProducer::SyncProducer(FrameSender send, NowFn now) : send_(std::move(send)), now_(std::move(now)) {}

void SyncProducer::start(Duration period, std::uint8_t counter_overflow) {
  if (period.count() <= 0) throw std::invalid_argument("SYNC period must be positive");
  if (counter_overflow == 1 || counter_overflow > 240)
    throw std::invalid_argument("SYNC counter overflow must be 0 or 2..240");
  period_ = period;
  overflow_ = counter_overflow;
  counter_ = 1;
  next_ = now_() + period_;
}

void SyncProducer::stop() { period_ = Duration::zero(); }

void SyncProducer::poll() {
  if (!running()) return;
  const TimePoint now = now_();
  if (now < next_) return;
  CanFrame f;
  f.id = cob::kSync;
  std::uint8_t sent = 0;
  if (overflow_ != 0) {
    sent = counter_;
    f.len = 1;
    f.data[0] = counter_;
    counter_ = counter_ >= overflow_ ? 1 : static_cast<std::uint8_t>(counter_ + 1);
  }
  send_(f);
  next_ = next_period(next_, now, period_);
  if (on_sync_) on_sync_(sent);
}

std::optional<TimePoint> SyncProducer::deadline() const {
  if (!running()) return std::nullopt;
  return next_;
}

namespace {
// 1984-01-01 00:00:00 UTC as seconds since the Unix epoch.
constexpr std::int64_t kCanopenEpoch = 441763200;
constexpr std::int64_t kMsPerDay = 86400000;
}  // namespace

CanFrame time_of_day_frame(std::chrono::system_clock::time_point t) {
  using namespace std::chrono;
  const std::int64_t ms = duration_cast<milliseconds>(t.time_since_epoch()).count() - kCanopenEpoch * 1000;
  const std::int64_t days = ms >= 0 ? ms / kMsPerDay : 0;
  const std::int64_t in_day = ms >= 0 ? ms % kMsPerDay : 0;
  CanFrame f;
  f.id = cob::kTime;
  f.len = 6;
  store_le<std::uint32_t>(std::span(f.data).subspan(0, 4), static_cast<std::uint32_t>(in_day) & 0x0FFFFFFF);
  store_le<std::uint16_t>(std::span(f.data).subspan(4, 2), static_cast<std::uint16_t>(days));
  return f;
}

TimeProducer::TimeProducer(FrameSender send, NowFn now, WallClockFn wall)
    : send_(std::move(send)), now_(std::move(now)), wall_(std::move(wall)) {}

void TimeProducer::start(Duration period) {
  period_ = period.count() > 0 ? period : Duration::zero();
  next_ = now_();
  poll();
}

void TimeProducer::poll() {
  if (period_.count() == 0) return;
  const TimePoint now = now_();
  if (now < next_) return;
  send_(time_of_day_frame(wall_()));
  next_ = next_period(next_, now, period_);
}

std::optional<TimePoint> TimeProducer::deadline() const {
  if (period_.count() == 0) return std::nullopt;
  return next_;
}

std::optional<std::chrono::system_clock::time_point> decode_time_of_day(const CanFrame& f) {
  using namespace std::chrono;
  if (f.id != cob::kTime || f.len != 6) return std::nullopt;
  const std::int64_t in_day = load_le<std::uint32_t>(f.payload().subspan(0, 4)) & 0x0FFFFFFF;
  const std::int64_t days = load_le<std::uint16_t>(f.payload().subspan(4, 2));
  return system_clock::time_point(milliseconds(kCanopenEpoch * 1000 + days * kMsPerDay + in_day));
}

}  // namespace advee::canopen
