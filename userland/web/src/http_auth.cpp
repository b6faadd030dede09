// SPDX-License-Identifier: GPL-2.0
#include "advee/web/http_auth.hpp"

#include <algorithm>

namespace advee::web {

std::string session_cookie_value(const std::string& header) {
  const std::string key = std::string(kSessionCookie) + "=";
  std::size_t pos = 0;
  while (pos < header.size()) {
    while (pos < header.size() && (header[pos] == ' ' || header[pos] == ';')) ++pos;
    const auto end = std::min(header.find(';', pos), header.size());
    if (header.compare(pos, key.size(), key) == 0) return header.substr(pos + key.size(), end - pos - key.size());
    pos = end;
  }
  return "";
}

namespace {
std::string cookie(const std::string& value, bool secure, const char* extra) {
  return std::string(kSessionCookie) + "=" + value + "; Path=/; HttpOnly; SameSite=Strict" +
         (secure ? "; Secure" : "") + extra;
}
}  // namespace

std::string session_set_cookie(const std::string& token, bool secure) { return cookie(token, secure, ""); }

std::string session_clear_cookie(bool secure) { return cookie("", secure, "; Max-Age=0"); }

bool origin_allowed(const std::string& origin, const std::string& host, const std::vector<std::string>& extra,
                    bool tls) {
  if (origin.empty()) return false;
  if (!host.empty() && ((!tls && origin == "http://" + host) || origin == "https://" + host)) return true;
  return std::find(extra.begin(), extra.end(), origin) != extra.end();
}

}  // namespace advee::web
