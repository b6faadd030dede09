// SPDX-License-Identifier: GPL-2.0
#include "advee/web/login_limiter.hpp"

#include <algorithm>

namespace advee::web {

void LoginLimiter::expire(std::deque<Clock::time_point>& times, Clock::time_point now) const {
  while (!times.empty() && now - times.front() >= window_) times.pop_front();
}

LoginLimiter::Clock::duration LoginLimiter::retry_after(const std::string& address, Clock::time_point now) {
  const auto it = failures_.find(address);
  if (it == failures_.end()) return Clock::duration::zero();
  expire(it->second, now);
  if (it->second.empty()) {
    failures_.erase(it);
    return Clock::duration::zero();
  }
  if (it->second.size() < max_failures_) return Clock::duration::zero();
  return it->second.front() + window_ - now;
}

void LoginLimiter::failed(const std::string& address, Clock::time_point now) {
  if (!failures_.count(address) && failures_.size() >= max_addresses_) {
    const auto stalest = std::min_element(failures_.begin(), failures_.end(), [](const auto& a, const auto& b) {
      return a.second.back() < b.second.back();
    });
    failures_.erase(stalest);
  }
  auto& times = failures_[address];
  expire(times, now);
  times.push_back(now);
  while (times.size() > max_failures_) times.pop_front();
}

void LoginLimiter::succeeded(const std::string& address) { failures_.erase(address); }

}  // namespace advee::web
