// SPDX-License-Identifier: GPL-2.0
#include <climits>
#include <cmath>
#include <sstream>

#include "advee/rs485sim/devices.hpp"

namespace advee::rs485sim {

void So1::set_ticks(std::int64_t left, std::int64_t right, Clock::time_point now) {
  base_ = {double(left), double(right)};
  base_time_ = now;
}

void So1::set_rate(double left_per_s, double right_per_s, Clock::time_point now) {
  const auto t = ticks(now);  // keep the count continuous across a rate change
  set_ticks(t[0], t[1], now);
  rate_ = {left_per_s, right_per_s};
}

std::array<std::int64_t, 2> So1::ticks(Clock::time_point now) const {
  const double dt = std::chrono::duration<double>(now - base_time_).count();
  return {std::llround(std::floor(base_[0] + rate_[0] * dt)),
          std::llround(std::floor(base_[1] + rate_[1] * dt))};
}

std::optional<Device::Result> So1::execute(std::uint8_t instr, std::span<const std::uint8_t> data,
                                           Clock::time_point now) {
  Result r;
  switch (instr) {
    case kGetTicks: {
      const unsigned width = data.empty() ? 2 : data[0];
      if (width != 1 && width != 2 && width != 4) {
        // The firmware refuses widths it does not have; data names the width.
        r.flags = kRespDevErr;
        r.data.push_back(static_cast<std::uint8_t>(width));
        return r;
      }
      for (auto t : ticks(now)) {
        // Two's complement truncated to the width: the counter wraps.
        const auto u = static_cast<std::uint64_t>(t);
        for (unsigned b = 0; b < width; ++b) r.data.push_back(static_cast<std::uint8_t>(u >> (8 * b)));
      }
      return r;
    }
    case kResetTicks: reset_state(now); return r;
    default: return std::nullopt;
  }
}

void So1::set(const std::string& key, const std::vector<std::string>& a) {
  const auto now = Clock::now();
  if (key == "ticks" && a.size() == 2) {
    set_ticks(parse_int(a[0], "left ticks", LONG_MIN, LONG_MAX),
              parse_int(a[1], "right ticks", LONG_MIN, LONG_MAX), now);
  } else if (key == "rate" && a.size() == 2) {
    set_rate(parse_double(a[0], "left ticks/s"), parse_double(a[1], "right ticks/s"), now);
  } else {
    throw UsageError("so1: set ticks LEFT RIGHT, set rate LEFT_PER_S RIGHT_PER_S");
  }
}

std::string So1::show(Clock::time_point now) const {
  const auto t = ticks(now);
  std::ostringstream o;
  o << "ticks " << t[0] << ' ' << t[1] << " rate " << rate_[0] << ' ' << rate_[1];
  return o.str();
}

}  // namespace advee::rs485sim
