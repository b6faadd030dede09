// SPDX-License-Identifier: GPL-2.0
// The client half of RFC 6455 that the bridge's tests speak by hand over a
// blocking asio stream (a plain tcp::socket or an ssl::stream of one): the
// upgrade request, masked client frames and the server's unmasked text
// frames. Written out rather than taken from websocketpp's client so that a
// test can send what no well-behaved client would (bad opcodes, oversized
// frames, forged headers).
#pragma once

#include <gtest/gtest.h>

#include <asio/read.hpp>
#include <asio/write.hpp>
#include <cstdint>
#include <string>
#include <system_error>

namespace advee::web::test {

// Sends the upgrade with `headers` (each ending in CRLF); returns the
// answer's head. The stream stays open after a 101; read byte by byte
// because the first frames may follow the head at once.
template <class Stream>
std::string websocket_upgrade(Stream& s, const std::string& host, const std::string& headers) {
  asio::write(s, asio::buffer("GET / HTTP/1.1\r\nHost: " + host + "\r\nUpgrade: websocket\r\nConnection: Upgrade\r\n" +
                              headers + "Sec-WebSocket-Key: dGhlIHNhbXBsZSBub25jZQ==\r\nSec-WebSocket-Version: 13\r\n\r\n"));
  std::string head;
  while (head.size() < 4 || head.compare(head.size() - 4, 4, "\r\n\r\n") != 0) {
    char c;
    std::error_code ec;
    asio::read(s, asio::buffer(&c, 1), ec);
    if (ec) break;
    head.push_back(c);
  }
  return head;
}

// One masked client frame (opcode 1 = text, 2 = binary), any length. A
// write error is left to the next read to show (the server closed).
template <class Stream>
void websocket_send(Stream& s, const std::string& payload, std::uint8_t opcode = 1) {
  std::string f;
  f.push_back(static_cast<char>(0x80 | opcode));
  if (payload.size() < 126) {
    f.push_back(static_cast<char>(0x80 | payload.size()));
  } else if (payload.size() < 65536) {
    f.push_back(static_cast<char>(0x80 | 126));
    f.push_back(static_cast<char>(payload.size() >> 8));
    f.push_back(static_cast<char>(payload.size() & 0xff));
  } else {
    f.push_back(static_cast<char>(0x80 | 127));
    for (int i = 7; i >= 0; --i) f.push_back(static_cast<char>((payload.size() >> (8 * i)) & 0xff));
  }
  const char mask[4] = {0x12, 0x34, 0x56, 0x78};
  f.append(mask, 4);
  for (std::size_t i = 0; i < payload.size(); ++i) f.push_back(payload[i] ^ mask[i % 4]);
  std::error_code ec;
  asio::write(s, asio::buffer(f), ec);
}

// One server frame's text (the bridge sends unmasked text frames only).
template <class Stream>
std::string websocket_read(Stream& s) {
  std::uint8_t h[2];
  asio::read(s, asio::buffer(h));
  EXPECT_EQ(h[0], 0x81);  // FIN + text
  std::uint64_t len = h[1] & 0x7f;
  if (len == 126) {
    std::uint8_t l[2];
    asio::read(s, asio::buffer(l));
    len = (l[0] << 8) | l[1];
  } else if (len == 127) {
    std::uint8_t l[8];
    asio::read(s, asio::buffer(l));
    len = 0;
    for (auto b : l) len = (len << 8) | b;
  }
  std::string payload(len, '\0');
  asio::read(s, asio::buffer(payload));
  return payload;
}

// Frames until one whose text starts with `prefix` (skips WEB_BRIDGE status
// and the other channels).
template <class Stream>
std::string websocket_read_until(Stream& s, const std::string& prefix) {
  for (;;) {
    auto f = websocket_read(s);
    if (f.rfind(prefix, 0) == 0) return f;
  }
}

}  // namespace advee::web::test
