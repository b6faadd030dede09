// SPDX-License-Identifier: GPL-2.0
// The HTTP + WebSocket side of advee-web, on one port: GET serves the page's
// files (and /scene.json), a WebSocket upgrade on any path subscribes the
// browser to every bridged message. Runs entirely on the io_context's thread.
//
// This header and bridge_server.cpp are C++17: Debian 12's websocketpp 0.8.2
// does not compile as C++20 (template-ids on constructors), so that one file
// is built as C++17 and only std:: types cross this interface.
#pragma once

#include <asio/io_context.hpp>
#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <functional>
#include <memory>
#include <string>
#include <vector>

#include "advee/web/control_request.hpp"

namespace advee::web {

struct BridgeOptions {
  std::string address = "127.0.0.1";
  std::uint16_t port = 8080;
  std::filesystem::path root;  // the page's files
  std::string scene_json = "{}";
  // A client whose socket has more than this unsent gets no more messages
  // until it drains; meanwhile its ClientQueue keeps only the newest per key.
  std::size_t max_buffered_bytes = 256 * 1024;
  // How often pending messages are retried and the status message is sent.
  std::uint32_t flush_interval_ms = 100;
  // History replayed to a new client (messages broadcast with keep).
  double history_s = 120;
  std::size_t history_max = 6000;

  // Control (docs/web-dashboard.md "Security model"). Operators and their
  // password hashes; empty path or no operators: nobody can log in.
  std::filesystem::path password_file;
  // false: anyone who reaches the port sees the live data (the robot's own
  // network); true: the WebSocket needs a logged-in session as well.
  bool view_requires_login = false;
  // Origins accepted besides the page's own (http(s)://Host).
  std::vector<std::string> allowed_origins;
  // The session cookie gets Secure: the page is reached over https through a
  // TLS proxy in front (with tls_cert the bridge sets it itself).
  bool secure_cookie = false;
  // HTTPS and WSS on the port instead of HTTP and WS: the PEM certificate
  // (chain, the server's first) and its unencrypted PEM private key; both or
  // neither. The constructor throws std::runtime_error naming the file when
  // one cannot be read or parsed, or when the key is not the certificate's.
  std::filesystem::path tls_cert, tls_key;
  DriveLimits drive_limits;
  // The lease holder's drive commands stopping for this long while it drives
  // (a page that hangs without closing) makes the bridge send the stop.
  std::uint32_t drive_timeout_ms = 500;
  std::size_t max_message_bytes = 64 * 1024;  // larger frames close the connection
};

// Who asked for a control action: the operator's name and address.
struct Operator {
  std::string name, address;
};

struct BridgeStats {
  std::size_t clients = 0;
  std::uint64_t messages = 0;  // broadcast() calls
  std::uint64_t dropped = 0;   // over every client, closed ones included
  std::uint64_t refused = 0;   // control messages refused (malformed, no login, no lease)
};

class BridgeServer {
 public:
  using Log = std::function<void(const std::string&)>;
  // Carries out an accepted control request (drive, stop, state, power,
  // homing: an LCM message) and, with `audit`, records it (log and
  // CM_DATA_ERROR notice); take and release come with audit only. Runs on
  // the io_context's thread. The bridge sends a stop by itself when the lease
  // holder goes (disconnect, logout, take-over) or its drive commands stop.
  using Control = std::function<void(const ControlRequest&, const Operator&, bool audit)>;
  // Listens at once; throws std::runtime_error (address in use, bad address,
  // TLS files).
  // Reads options.password_file (throws std::runtime_error naming a bad line).
  BridgeServer(asio::io_context& io, BridgeOptions options, Log log, Control control = nullptr);
  ~BridgeServer();
  BridgeServer(const BridgeServer&) = delete;
  BridgeServer& operator=(const BridgeServer&) = delete;

  // One message for every client (and for the snapshot that a newly
  // connected client gets first; with `keep`, also for the history replayed
  // to it before that). Call on the io_context's thread.
  void broadcast(const std::string& key, const std::string& payload, bool keep = false);

  // Stops listening and closes every connection (going away).
  void shutdown();

  BridgeStats stats() const;
  // The port really listened on (options.port 0 picks a free one).
  std::uint16_t port() const;

 private:
  struct Impl;  // the interface below
  template <class Config>
  struct ImplT;  // the server over plain TCP or TLS (websocketpp config)
  std::unique_ptr<Impl> impl_;
};

}  // namespace advee::web
