// SPDX-License-Identifier: GPL-2.0
#include "advee/web/session_store.hpp"

#include <sodium.h>

#include <algorithm>

namespace advee::web {

namespace {
std::string to_hex(const unsigned char* p, std::size_t n) {
  std::string s(n * 2 + 1, '\0');
  sodium_bin2hex(s.data(), s.size(), p, n);
  s.pop_back();
  return s;
}
}  // namespace

std::string SessionStore::digest(const std::string& token) {
  unsigned char h[crypto_generichash_BYTES];
  crypto_generichash(h, sizeof h, reinterpret_cast<const unsigned char*>(token.data()), token.size(),
                     nullptr, 0);
  return to_hex(h, sizeof h);
}

std::string SessionStore::create(const std::string& user, Clock::time_point now) {
  while (sessions_.size() >= max_sessions_ && !sessions_.empty()) {
    const auto oldest = std::min_element(sessions_.begin(), sessions_.end(), [](const auto& a, const auto& b) {
      return a.second.last_used < b.second.last_used;
    });
    sessions_.erase(oldest);
  }
  unsigned char raw[32];
  randombytes_buf(raw, sizeof raw);
  const std::string token = to_hex(raw, sizeof raw);
  sessions_[digest(token)] = Session{user, now, now};
  return token;
}

std::optional<std::string> SessionStore::user(const std::string& token, Clock::time_point now) {
  if (token.size() != 64) return std::nullopt;
  const auto it = sessions_.find(digest(token));
  if (it == sessions_.end()) return std::nullopt;
  if (now - it->second.last_used > idle_timeout_) {
    sessions_.erase(it);
    return std::nullopt;
  }
  it->second.last_used = now;
  return it->second.user;
}

void SessionStore::revoke(const std::string& token) { sessions_.erase(digest(token)); }

}  // namespace advee::web
