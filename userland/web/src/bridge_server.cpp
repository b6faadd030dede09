// SPDX-License-Identifier: GPL-2.0
// Built as C++17: see bridge_server.hpp.
#include "advee/web/bridge_server.hpp"

#include <asio/steady_timer.hpp>
#include <chrono>
#include <map>
#include <stdexcept>
#include <utility>
#include <websocketpp/config/asio_no_tls.hpp>
#include <websocketpp/server.hpp>

#include "advee/web/client_queue.hpp"
#include "advee/web/history.hpp"
#include "advee/web/static_files.hpp"

namespace advee::web {

namespace {
using Server = websocketpp::server<websocketpp::config::asio>;
using Hdl = websocketpp::connection_hdl;

constexpr std::size_t kMaxSnapshotKeys = 1024;
constexpr int kStatusEveryFlushes = 10;

std::int64_t utime_now() {
  return std::chrono::duration_cast<std::chrono::microseconds>(
             std::chrono::system_clock::now().time_since_epoch())
      .count();
}
}  // namespace

struct BridgeServer::Impl {
  struct Client {
    ClientQueue queue;
  };

  asio::io_context& io;
  BridgeOptions opt;
  Log log;
  Server server;
  asio::steady_timer flush_timer;
  std::map<Hdl, Client, std::owner_less<Hdl>> clients;
  std::map<std::string, std::string> snapshot;  // newest message per key
  History history;
  std::uint64_t messages = 0;
  std::uint64_t dropped_closed = 0;  // drops of clients that have gone
  int flushes = 0;
  bool stopping = false;

  Impl(asio::io_context& io_, BridgeOptions o, Log l)
      : io(io_),
        opt(std::move(o)),
        log(std::move(l)),
        flush_timer(io_),
        history(opt.history_s, opt.history_max) {}

  void start() {
    server.clear_access_channels(websocketpp::log::alevel::all);
    server.clear_error_channels(websocketpp::log::elevel::all);
    std::error_code ec;
    server.init_asio(&io, ec);
    if (ec) throw std::runtime_error("cannot set up the server: " + ec.message());
    server.set_reuse_addr(true);
    server.set_http_handler([this](Hdl h) { on_http(h); });
    server.set_open_handler([this](Hdl h) { on_open(h); });
    server.set_close_handler([this](Hdl h) { on_close(h); });
    server.set_fail_handler([this](Hdl h) { on_fail(h); });

    const auto addr = asio::ip::make_address(opt.address, ec);
    if (ec) throw std::runtime_error("bad listen address " + opt.address + ": " + ec.message());
    server.listen(asio::ip::tcp::endpoint(addr, opt.port), ec);
    if (ec)
      throw std::runtime_error("cannot listen on " + opt.address + ":" +
                               std::to_string(opt.port) + ": " + ec.message());
    server.start_accept(ec);
    if (ec) throw std::runtime_error("cannot accept connections: " + ec.message());
    arm_flush_timer();
  }

  void arm_flush_timer() {
    flush_timer.expires_after(std::chrono::milliseconds(opt.flush_interval_ms));
    flush_timer.async_wait([this](const std::error_code& ec) {
      if (ec || stopping) return;
      if (++flushes % kStatusEveryFlushes == 0) send_status();
      for (auto& [hdl, client] : clients) flush(hdl, client);
      arm_flush_timer();
    });
  }

  void on_http(Hdl h) {
    std::error_code ec;
    auto con = server.get_con_from_hdl(h, ec);
    if (ec) return;
    const std::string& method = con->get_request().get_method();
    con->append_header("Cache-Control", "no-cache");
    if (method != "GET" && method != "HEAD") {
      con->set_status(websocketpp::http::status_code::method_not_allowed);
      con->append_header("Allow", "GET, HEAD");
      return;
    }
    const std::string target = con->get_resource();
    if (target == "/scene.json" || target.rfind("/scene.json?", 0) == 0) {
      con->append_header("Content-Type", "application/json");
      con->set_body(opt.scene_json);
      con->set_status(websocketpp::http::status_code::ok);
      return;
    }
    const auto file = resolve_static(opt.root, target);
    const auto body = file ? read_file(*file) : std::nullopt;
    if (!body) {
      con->append_header("Content-Type", "text/plain; charset=utf-8");
      con->set_body("not found\n");
      con->set_status(websocketpp::http::status_code::not_found);
      return;
    }
    con->append_header("Content-Type", std::string(content_type(*file)));
    con->set_body(*body);
    con->set_status(websocketpp::http::status_code::ok);
  }

  void on_open(Hdl h) {
    if (stopping) return;
    auto& client = clients[h];
    // First the newest of everything (small: the page shows the present at
    // once), then the history as one frame, {"channel":"WEB_HISTORY",
    // "messages":[...]}, for trails and plots; straight to the socket (it is
    // bounded, and the queue would coalesce it).
    for (const auto& [key, payload] : snapshot) client.queue.push(key, payload);
    flush(h, client);
    send_status(h, client);
    if (history.size() > 0) {
      std::string bundle = R"({"channel":"WEB_HISTORY","messages":[)";
      for (const auto& payload : history.payloads()) {
        bundle += payload;
        bundle += ',';
      }
      bundle.back() = ']';
      bundle += '}';
      std::error_code ec;
      server.send(h, bundle, websocketpp::frame::opcode::text, ec);
    }
  }

  void forget(Hdl h) {
    const auto it = clients.find(h);
    if (it == clients.end()) return;
    dropped_closed += it->second.queue.dropped();
    if (it->second.queue.dropped() > 0)
      log("client closed after " + std::to_string(it->second.queue.dropped()) +
          " dropped messages");
    clients.erase(it);
  }

  void on_close(Hdl h) { forget(h); }

  void on_fail(Hdl h) {
    std::error_code ec;
    auto con = server.get_con_from_hdl(h, ec);
    if (!ec && !stopping) log("connection failed: " + con->get_ec().message());
    forget(h);
  }

  // Sends what is pending unless the socket still holds too much unsent.
  void flush(Hdl h, Client& client) {
    if (client.queue.pending() == 0) return;
    std::error_code ec;
    auto con = server.get_con_from_hdl(h, ec);
    if (ec || con->get_state() != websocketpp::session::state::open) return;
    if (con->get_buffered_amount() > opt.max_buffered_bytes) return;
    for (const auto& payload : client.queue.take_all()) {
      server.send(h, payload, websocketpp::frame::opcode::text, ec);
      if (ec) return;  // closing: the close handler forgets it
    }
  }

  // The status goes straight out, never queued: a client too slow to take it
  // gets the next one a second later.
  void send_status(Hdl hdl, const Client& client) {
    std::error_code ec;
    auto con = server.get_con_from_hdl(hdl, ec);
    if (ec || con->get_state() != websocketpp::session::state::open ||
        con->get_buffered_amount() > opt.max_buffered_bytes)
      return;
    const std::string s =
        std::string("{\"channel\":\"WEB_BRIDGE\",\"utime\":") + std::to_string(utime_now()) +
        ",\"clients\":" + std::to_string(clients.size()) +
        ",\"messages\":" + std::to_string(messages) +
        ",\"dropped\":" + std::to_string(client.queue.dropped()) + "}";
    server.send(hdl, s, websocketpp::frame::opcode::text, ec);
  }

  void send_status() {
    for (auto& [hdl, client] : clients) send_status(hdl, client);
  }

  void broadcast(const std::string& key, const std::string& payload, bool keep) {
    if (stopping) return;
    ++messages;
    if (keep)
      history.add(std::chrono::duration<double>(std::chrono::steady_clock::now().time_since_epoch()).count(),
                  payload);
    if (snapshot.size() < kMaxSnapshotKeys || snapshot.count(key)) snapshot[key] = payload;
    for (auto& [hdl, client] : clients) {
      client.queue.push(key, payload);
      flush(hdl, client);
    }
  }

  void shutdown() {
    if (stopping) return;
    stopping = true;
    flush_timer.cancel();
    std::error_code ec;
    server.stop_listening(ec);
    for (auto& [hdl, client] : clients) {
      server.close(hdl, websocketpp::close::status::going_away, "advee-web stops", ec);
      dropped_closed += client.queue.dropped();
    }
    clients.clear();
  }
};

BridgeServer::BridgeServer(asio::io_context& io, BridgeOptions options, Log log)
    : impl_(std::make_unique<Impl>(io, std::move(options), std::move(log))) {
  impl_->start();
}

BridgeServer::~BridgeServer() {
  if (impl_) impl_->shutdown();
}

void BridgeServer::broadcast(const std::string& key, const std::string& payload, bool keep) {
  impl_->broadcast(key, payload, keep);
}

void BridgeServer::shutdown() { impl_->shutdown(); }

BridgeStats BridgeServer::stats() const {
  BridgeStats s;
  s.clients = impl_->clients.size();
  s.messages = impl_->messages;
  s.dropped = impl_->dropped_closed;
  for (const auto& [hdl, client] : impl_->clients) s.dropped += client.queue.dropped();
  return s;
}

std::uint16_t BridgeServer::port() const {
  std::error_code ec;
  const auto ep = impl_->server.get_local_endpoint(ec);
  return ec ? 0 : ep.port();
}

}  // namespace advee::web
