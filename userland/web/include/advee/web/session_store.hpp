// SPDX-License-Identifier: GPL-2.0
// Logged-in operators: a session is a random 256-bit token (the cookie's
// value) that names an operator until it is revoked (logout) or idle longer
// than the timeout. Only a hash of each token is kept, so the store's
// lookups do not depend on how much of a guessed token is right.
// C++17: bridge_server.cpp includes it.
#pragma once

#include <chrono>
#include <cstddef>
#include <map>
#include <optional>
#include <string>

namespace advee::web {

class SessionStore {
 public:
  using Clock = std::chrono::steady_clock;
  // init_crypto() must have run.
  explicit SessionStore(std::chrono::seconds idle_timeout = std::chrono::hours(8),
                        std::size_t max_sessions = 64)
      : idle_timeout_(idle_timeout), max_sessions_(max_sessions) {}

  // A new session for `user`; returns its token (64 hex digits). The oldest
  // session goes when there are max_sessions.
  std::string create(const std::string& user, Clock::time_point now = Clock::now());

  // The operator of `token`, nullopt for an unknown, revoked or expired one;
  // a valid lookup keeps the session alive.
  std::optional<std::string> user(const std::string& token, Clock::time_point now = Clock::now());

  void revoke(const std::string& token);
  std::size_t size() const { return sessions_.size(); }

 private:
  struct Session {
    std::string user;
    Clock::time_point created, last_used;
  };
  static std::string digest(const std::string& token);
  std::chrono::seconds idle_timeout_;
  std::size_t max_sessions_;
  std::map<std::string, Session> sessions_;  // by digest(token)
};

}  // namespace advee::web
