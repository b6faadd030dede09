// SPDX-License-Identifier: GPL-2.0
// The HTTP side of a login: the session cookie (its one name and its
// attributes) and the Origin check of the WebSocket upgrade and of POSTs.
// C++17: bridge_server.cpp includes it.
#pragma once

#include <string>
#include <vector>

namespace advee::web {

inline constexpr const char* kSessionCookie = "advee_session";

// The value of advee_session in a Cookie header, "" when absent.
std::string session_cookie_value(const std::string& cookie_header);

// Set-Cookie for a new session: HttpOnly (no script reads it), SameSite=Strict
// (no other site's page sends it), Path=/, Secure when served over TLS; no
// Max-Age (the browser forgets it when it closes; the server expires it too).
std::string session_set_cookie(const std::string& token, bool secure);
// Set-Cookie that makes the browser forget it (logout).
std::string session_clear_cookie(bool secure);

// A browser's request comes from our own page when its Origin is
// http(s)://HOST with HOST the Host header it sent, or one of `extra`
// (--allow-origin, e.g. a reverse proxy's name). An absent Origin is refused:
// every browser sends one on WebSocket upgrades and POSTs. With `tls` (the
// bridge itself speaks TLS) only https://HOST is our own page: nothing on
// that port is served over plain http, so an http:// Origin with that host
// and port is not ours.
bool origin_allowed(const std::string& origin, const std::string& host,
                    const std::vector<std::string>& extra, bool tls = false);

}  // namespace advee::web
