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
};

struct BridgeStats {
  std::size_t clients = 0;
  std::uint64_t messages = 0;  // broadcast() calls
  std::uint64_t dropped = 0;   // over every client, closed ones included
};

class BridgeServer {
 public:
  using Log = std::function<void(const std::string&)>;
  // Listens at once; throws std::runtime_error (address in use, bad address).
  BridgeServer(asio::io_context& io, BridgeOptions options, Log log);
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
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace advee::web
