// SPDX-License-Identifier: GPL-2.0
// Failed logins are rate-limited per client address: after `max_failures`
// failures within `window`, that address may not try again until the window
// since its oldest counted failure has passed (a password guesser gets
// max_failures tries per window). A success clears the address's record.
// The number of addresses kept is bounded (the stalest goes first).
// C++17: bridge_server.cpp includes it.
#pragma once

#include <chrono>
#include <cstddef>
#include <deque>
#include <map>
#include <string>

namespace advee::web {

class LoginLimiter {
 public:
  using Clock = std::chrono::steady_clock;
  explicit LoginLimiter(std::size_t max_failures = 5,
                        std::chrono::seconds window = std::chrono::seconds(60),
                        std::size_t max_addresses = 4096)
      : max_failures_(max_failures), window_(window), max_addresses_(max_addresses) {}

  // Zero when `address` may try now, else how long until it may.
  Clock::duration retry_after(const std::string& address, Clock::time_point now = Clock::now());
  void failed(const std::string& address, Clock::time_point now = Clock::now());
  void succeeded(const std::string& address);
  std::size_t addresses() const { return failures_.size(); }

 private:
  void expire(std::deque<Clock::time_point>& times, Clock::time_point now) const;
  std::size_t max_failures_;
  std::chrono::seconds window_;
  std::size_t max_addresses_;
  std::map<std::string, std::deque<Clock::time_point>> failures_;
};

}  // namespace advee::web
