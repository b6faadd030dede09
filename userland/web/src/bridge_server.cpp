// SPDX-License-Identifier: GPL-2.0
// Built as C++17: see bridge_server.hpp.
#include "advee/web/bridge_server.hpp"

#include <asio/post.hpp>
#include <asio/steady_timer.hpp>
#include <asio/thread_pool.hpp>
#include <atomic>
#include <chrono>
#include <map>
#include <nlohmann/json.hpp>
#include <optional>
#include <stdexcept>
#include <utility>
#include <openssl/err.h>
#include <openssl/ssl.h>
#include <openssl/x509.h>
#include <cerrno>
#include <cstdio>
#include <cstring>
#include <websocketpp/config/asio.hpp>
#include <websocketpp/config/asio_no_tls.hpp>
#include <websocketpp/server.hpp>

#include "advee/web/client_queue.hpp"
#include "advee/web/history.hpp"
#include "advee/web/http_auth.hpp"
#include "advee/web/login_limiter.hpp"
#include "advee/web/password_file.hpp"
#include "advee/web/session_store.hpp"
#include "advee/web/static_files.hpp"

namespace advee::web {

namespace {
using Hdl = websocketpp::connection_hdl;

constexpr std::size_t kMaxSnapshotKeys = 1024;
constexpr int kStatusEveryFlushes = 10;
constexpr std::size_t kMaxHttpBody = 4096;
// Password checks run off the io thread, one at a time (each takes 19 MiB
// and tens of ms, more on ARM);
// beyond this many at once a login is answered 503.
constexpr int kMaxLoginsInFlight = 2;

// Keys in the order written: channel first, as in every other frame.
using json = nlohmann::ordered_json;
using Clock = std::chrono::steady_clock;

std::string json_reply(const json& j) { return j.dump(); }

// The newest OpenSSL error as text ("" when there is none); clears the queue.
std::string openssl_error() {
  unsigned long e = 0, last = 0;
  while ((e = ERR_get_error()) != 0) last = e;
  if (last == 0) return "";
  char buf[256];
  ERR_error_string_n(last, buf, sizeof buf);
  return buf;
}

// The file can be opened for reading: the message names the file and errno,
// clearer than OpenSSL's "system lib" error for a missing file.
void check_readable(const std::filesystem::path& file, const char* what) {
  std::FILE* f = std::fopen(file.c_str(), "rb");
  if (!f) throw std::runtime_error(std::string(what) + " " + file.string() + ": " + std::strerror(errno));
  std::fclose(f);
}

// One TLS context for every connection: certificate chain and key loaded
// and matched once at start, so that a bad file stops advee-web at once
// instead of failing every handshake later. TLS 1.2 at least (1.0 and 1.1
// are deprecated, RFC 8996), no compression (CRIME), the server's cipher
// order, TLS 1.2 ciphers only with forward secrecy and AEAD (TLS 1.3's are
// all such); no stateless session tickets, so no ticket key lives for the
// process's whole life (resumption uses the in-memory session cache).
std::shared_ptr<asio::ssl::context> make_tls_context(const std::filesystem::path& cert,
                                                     const std::filesystem::path& key) {
  check_readable(cert, "TLS certificate");
  check_readable(key, "TLS key");
  auto ctx = std::make_shared<asio::ssl::context>(asio::ssl::context::tls_server);
  SSL_CTX* native = ctx->native_handle();
  ctx->set_options(asio::ssl::context::default_workarounds | asio::ssl::context::no_compression |
                   asio::ssl::context::single_dh_use);
  SSL_CTX_set_options(native, SSL_OP_CIPHER_SERVER_PREFERENCE | SSL_OP_NO_TICKET | SSL_OP_NO_RENEGOTIATION);
  if (SSL_CTX_set_min_proto_version(native, TLS1_2_VERSION) != 1)
    throw std::runtime_error("TLS: cannot require TLS 1.2: " + openssl_error());
  if (SSL_CTX_set_cipher_list(native,
                              "ECDHE-ECDSA-AES128-GCM-SHA256:ECDHE-RSA-AES128-GCM-SHA256:"
                              "ECDHE-ECDSA-AES256-GCM-SHA384:ECDHE-RSA-AES256-GCM-SHA384:"
                              "ECDHE-ECDSA-CHACHA20-POLY1305:ECDHE-RSA-CHACHA20-POLY1305") != 1)
    throw std::runtime_error("TLS: cipher list refused: " + openssl_error());
  // An encrypted key would make OpenSSL ask for its passphrase on the
  // terminal (a service has none): an empty passphrase fails it instead.
  ctx->set_password_callback([](std::size_t, asio::ssl::context::password_purpose) { return std::string(); });
  std::error_code ec;
  ctx->use_certificate_chain_file(cert.string(), ec);
  if (ec)
    throw std::runtime_error("TLS certificate " + cert.string() + ": not a PEM certificate (" + ec.message() + ")");
  ctx->use_private_key_file(key.string(), asio::ssl::context::pem, ec);
  // OpenSSL compares the key with the certificate already here.
  const bool mismatch = ec && ec.category() == asio::error::get_ssl_category() &&
                        ERR_GET_REASON(static_cast<unsigned long>(ec.value())) == X509_R_KEY_VALUES_MISMATCH;
  if (ec && !mismatch)
    throw std::runtime_error("TLS key " + key.string() + ": not an unencrypted PEM private key (" + ec.message() +
                             ")");
  if (mismatch || SSL_CTX_check_private_key(native) != 1)
    throw std::runtime_error("TLS key " + key.string() + " does not belong to the certificate " + cert.string());
  return ctx;
}

std::int64_t utime_now() {
  return std::chrono::duration_cast<std::chrono::microseconds>(
             std::chrono::system_clock::now().time_since_epoch())
      .count();
}
}  // namespace

// What BridgeServer needs of its server, whichever transport it has.
struct BridgeServer::Impl {
  virtual ~Impl() = default;
  virtual void start() = 0;
  virtual void broadcast(const std::string& key, const std::string& payload, bool keep) = 0;
  virtual void shutdown() = 0;
  virtual BridgeStats stats() const = 0;
  virtual std::uint16_t port() const = 0;
};

// The server over plain TCP (websocketpp::config::asio) or over TLS
// (config::asio_tls): the same code, only the socket differs.
template <class Config>
struct BridgeServer::ImplT final : BridgeServer::Impl {
  using Server = websocketpp::server<Config>;
  using connection_ptr = typename Server::connection_ptr;
  using message_ptr = typename Server::message_ptr;
  static constexpr bool kTls = std::is_same_v<Config, websocketpp::config::asio_tls>;

  struct Client {
    ClientQueue queue;
    std::string token;    // the session cookie sent with the upgrade ("" = none)
    std::string address;  // the peer's IP address
    bool driving = false; // the last drive command was not a stop
    Clock::time_point last_drive{};
  };

  asio::io_context& io;
  BridgeOptions opt;
  Log log;
  Control control;
  SessionStore sessions;
  LoginLimiter limiter;
  asio::thread_pool login_pool{1};
  std::atomic<int> logins_in_flight{0};
  std::optional<Hdl> holder;  // the connection holding the control lease
  std::string holder_name;
  std::uint64_t refused = 0;
  Server server;
  asio::steady_timer flush_timer;
  std::map<Hdl, Client, std::owner_less<Hdl>> clients;
  std::map<std::string, std::string> snapshot;  // newest message per key
  History history;
  std::uint64_t messages = 0;
  std::uint64_t dropped_closed = 0;  // drops of clients that have gone
  int flushes = 0;
  bool stopping = false;

  std::shared_ptr<asio::ssl::context> tls;  // with TLS only

  ImplT(asio::io_context& io_, BridgeOptions o, Log l, Control c)
      : io(io_),
        opt(std::move(o)),
        log(std::move(l)),
        control(std::move(c)),
        flush_timer(io_),
        history(opt.history_s, opt.history_max) {
    init_crypto();
    if constexpr (kTls) {
      tls = make_tls_context(opt.tls_cert, opt.tls_key);
      opt.secure_cookie = true;  // the page is served over https: the cookie never goes out in clear
    }
    if (!opt.password_file.empty()) {
      const auto n = PasswordFile::load(opt.password_file).size();
      log(opt.password_file.string() + ": " + std::to_string(n) + " operator(s)" +
          (n == 0 ? " (nobody can log in: advee-web passwd NAME)" : ""));
    }
  }

  void start() override {
    server.clear_access_channels(websocketpp::log::alevel::all);
    server.clear_error_channels(websocketpp::log::elevel::all);
    std::error_code ec;
    server.init_asio(&io, ec);
    if (ec) throw std::runtime_error("cannot set up the server: " + ec.message());
    server.set_reuse_addr(true);
    if constexpr (kTls) server.set_tls_init_handler([this](Hdl) { return tls; });
    server.set_http_handler([this](Hdl h) { on_http(h); });
    server.set_open_handler([this](Hdl h) { on_open(h); });
    server.set_close_handler([this](Hdl h) { on_close(h); });
    server.set_fail_handler([this](Hdl h) { on_fail(h); });
    server.set_validate_handler([this](Hdl h) { return on_validate(h); });
    server.set_message_handler([this](Hdl h, message_ptr m) { on_message(h, m); });
    server.set_max_message_size(opt.max_message_bytes);
    server.set_max_http_body_size(kMaxHttpBody);

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
      check_drive_timeout();
      for (auto& [hdl, client] : clients) flush(hdl, client);
      arm_flush_timer();
    });
  }

  void on_http(Hdl h) {
    std::error_code ec;
    auto con = server.get_con_from_hdl(h, ec);
    if (ec) return;
    const std::string& method = con->get_request().get_method();
    const std::string target = con->get_resource();
    con->append_header("Cache-Control", "no-cache");
    if (method == "POST" && (target == "/login" || target == "/logout")) {
      con->append_header("Content-Type", "application/json");
      if (!origin_allowed(con->get_request_header("Origin"), con->get_request_header("Host"),
                          opt.allowed_origins, kTls)) {
        con->set_body(json_reply({{"error", "wrong or missing Origin"}}));
        con->set_status(websocketpp::http::status_code::forbidden);
        return;
      }
      if (target == "/login")
        on_login(con);
      else
        on_logout(con);
      return;
    }
    if (method != "GET" && method != "HEAD") {
      con->set_status(websocketpp::http::status_code::method_not_allowed);
      con->append_header("Allow", "GET, HEAD");
      return;
    }
    if (target == "/session") {
      const auto token = session_cookie_value(con->get_request_header("Cookie"));
      const auto user = sessions.user(token);
      con->append_header("Content-Type", "application/json");
      con->set_body(json_reply({{"user", user ? json(*user) : json(nullptr)},
                                {"view_requires_login", opt.view_requires_login},
                                {"max_speed_mps", opt.drive_limits.max_speed_mps},
                                {"max_steering_rad", opt.drive_limits.max_steering_rad},
                                {"drive_timeout_ms", opt.drive_timeout_ms}}));
      con->set_status(websocketpp::http::status_code::ok);
      return;
    }
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

  static std::string peer_address(const connection_ptr& con) {
    std::error_code ec;
    const auto ep = con->get_raw_socket().remote_endpoint(ec);
    if (ec) return "?";
    auto a = ep.address();
    if (a.is_v6() && a.to_v6().is_v4_mapped()) a = asio::ip::make_address_v4(asio::ip::v4_mapped, a.to_v6());
    return a.to_string();
  }

  // POST /login {"user":..,"password":..}: 200 + the cookie, 401, 429 (rate
  // limit, Retry-After), 400, 503 (too many checks at once).
  void on_login(const connection_ptr& con) {
    const std::string address = peer_address(con);
    const auto wait = limiter.retry_after(address);
    if (wait > Clock::duration::zero()) {
      const auto s = std::chrono::duration_cast<std::chrono::seconds>(wait).count() + 1;
      con->append_header("Retry-After", std::to_string(s));
      con->set_body(json_reply({{"error", "too many failed logins: try again in " + std::to_string(s) + " s"}}));
      con->set_status(websocketpp::http::status_code::too_many_requests);
      log("login refused for " + address + ": rate limit");
      return;
    }
    const json body = json::parse(con->get_request_body(), nullptr, false);
    if (!body.is_object() || !body.contains("user") || !body["user"].is_string() || !body.contains("password") ||
        !body["password"].is_string() || !valid_operator_name(body["user"].get<std::string>())) {
      con->set_body(json_reply({{"error", "expected {\"user\":..,\"password\":..}"}}));
      con->set_status(websocketpp::http::status_code::bad_request);
      return;
    }
    if (opt.password_file.empty() || logins_in_flight >= kMaxLoginsInFlight) {
      con->set_body(json_reply({{"error", opt.password_file.empty() ? "no operators configured" : "busy"}}));
      con->set_status(websocketpp::http::status_code::service_unavailable);
      return;
    }
    if (con->defer_http_response()) return;
    ++logins_in_flight;
    // The file is read for every login: advee-web passwd needs no restart.
    asio::post(login_pool, [this, con, address, user = body["user"].get<std::string>(),
                            password = body["password"].get<std::string>()] {
      bool ok = false;
      std::string problem;
      try {
        ok = PasswordFile::load(opt.password_file).check(user, password);
      } catch (const std::exception& e) {
        problem = e.what();
      }
      asio::post(io, [this, con, address, user, ok, problem] { finish_login(con, address, user, ok, problem); });
    });
  }

  void finish_login(const connection_ptr& con, const std::string& address, const std::string& user,
                    bool ok, const std::string& problem) {
    --logins_in_flight;
    if (stopping) return;
    if (!problem.empty()) log(problem);
    if (ok) {
      limiter.succeeded(address);
      con->append_header("Set-Cookie", session_set_cookie(sessions.create(user), opt.secure_cookie));
      con->set_body(json_reply({{"user", user}}));
      con->set_status(websocketpp::http::status_code::ok);
      log("login: " + user + " from " + address);
    } else {
      limiter.failed(address);
      con->set_body(json_reply({{"error", "wrong name or password"}}));
      con->set_status(websocketpp::http::status_code::unauthorized);
      log("login failed: " + user + " from " + address);
    }
    std::error_code ec;
    con->send_http_response(ec);
  }

  void on_logout(const connection_ptr& con) {
    const auto token = session_cookie_value(con->get_request_header("Cookie"));
    const auto user = sessions.user(token);
    sessions.revoke(token);
    // The session's WebSockets lose the lease (and stop the robot).
    if (holder && clients.count(*holder) && clients[*holder].token == token && !token.empty())
      drop_lease("logged out");
    con->append_header("Set-Cookie", session_clear_cookie(opt.secure_cookie));
    con->set_body(json_reply({{"user", nullptr}}));
    con->set_status(websocketpp::http::status_code::ok);
    if (user) log("logout: " + *user + " from " + peer_address(con));
  }

  // The WebSocket upgrade: our own page's Origin only; a session when
  // viewing needs a login.
  bool on_validate(Hdl h) {
    std::error_code ec;
    auto con = server.get_con_from_hdl(h, ec);
    if (ec || stopping) return false;
    if (!origin_allowed(con->get_request_header("Origin"), con->get_request_header("Host"),
                        opt.allowed_origins, kTls)) {
      log("WebSocket refused for " + peer_address(con) + ": Origin '" + con->get_request_header("Origin") + "'");
      con->set_status(websocketpp::http::status_code::forbidden);
      return false;
    }
    if (opt.view_requires_login && !sessions.user(session_cookie_value(con->get_request_header("Cookie")))) {
      con->set_status(websocketpp::http::status_code::unauthorized);
      return false;
    }
    return true;
  }

  bool is_holder(const Hdl& h) const { return holder && !holder->owner_before(h) && !h.owner_before(*holder); }

  void send_to(Hdl h, const json& j) {
    std::error_code ec;
    server.send(h, j.dump(), websocketpp::frame::opcode::text, ec);
  }

  // WEB_LEASE to every client: who holds control, and whether it is them.
  void send_lease(const std::string& event = "", const std::string& by = "") {
    for (auto& [hdl, client] : clients) {
      json j = {{"channel", "WEB_LEASE"},
                {"holder", holder ? json(holder_name) : json(nullptr)},
                {"you", is_holder(hdl)}};
      if (!event.empty()) j["event"] = event;
      if (!by.empty()) j["by"] = by;
      send_to(hdl, j);
    }
  }

  Operator operator_of(const Client& c, const std::string& name) const { return {name, c.address}; }

  void stop_robot(const Operator& who, const std::string& why) {
    ControlRequest stop;
    stop.kind = ControlRequest::Kind::stop;
    stop.cause = why;
    if (control) control(stop, who, true);
  }

  // The holder loses the lease (disconnect, logout, take-over); the robot stops.
  void drop_lease(const std::string& why, const std::string& by = "") {
    if (!holder) return;
    const auto it = clients.find(*holder);
    stop_robot({holder_name, it != clients.end() ? it->second.address : "?"}, why);
    if (it != clients.end()) it->second.driving = false;
    holder.reset();
    holder_name.clear();
    send_lease(by.empty() ? "released" : "taken", by);
  }

  void check_drive_timeout() {
    if (!holder) return;
    const auto it = clients.find(*holder);
    if (it == clients.end() || !it->second.driving) return;
    if (Clock::now() - it->second.last_drive < std::chrono::milliseconds(opt.drive_timeout_ms)) return;
    it->second.driving = false;
    stop_robot(operator_of(it->second, holder_name),
               "no drive command for " + std::to_string(opt.drive_timeout_ms) + " ms");
  }

  void refuse(Hdl h, const std::string& why) {
    ++refused;
    send_to(h, {{"channel", "WEB_CONTROL"}, {"ok", false}, {"error", why}});
  }

  void on_message(Hdl h, const message_ptr& m) {
    const auto it = clients.find(h);
    if (it == clients.end() || stopping) return;
    Client& client = it->second;
    if (m->get_opcode() != websocketpp::frame::opcode::text) return refuse(h, "not a text message");
    const auto parsed = parse_control_request(m->get_payload(), opt.drive_limits);
    if (!parsed.request) return refuse(h, parsed.error);
    const ControlRequest& r = *parsed.request;
    const auto user = sessions.user(client.token);
    if (!user) return refuse(h, "login required");
    const bool holds = is_holder(h);
    using K = ControlRequest::Kind;
    if (r.kind == K::take) {
      if (holds) return send_lease();
      if (holder && !r.force) return refuse(h, "control is held by " + holder_name);
      const std::string previous = holder_name;
      if (holder) drop_lease("taken over by " + *user, *user);
      holder = h;
      holder_name = *user;
      if (control) control(r, operator_of(client, *user), true);
      return send_lease("taken", previous.empty() ? "" : *user);
    }
    if (!holds) return refuse(h, holder ? "control is held by " + holder_name : "take control first");
    if (r.kind == K::release) {
      if (control) control(r, operator_of(client, *user), true);
      return drop_lease("released");
    }
    const bool moving = r.kind == K::drive && (r.speed_mps != 0 || r.steering_rad != 0);
    // Driving is logged when it starts and stops, not at every command.
    const bool audit = r.kind != K::drive ? (r.kind != K::stop || client.driving) : (moving && !client.driving);
    if (r.kind == K::drive || r.kind == K::stop) {
      client.driving = moving;
      client.last_drive = Clock::now();
    }
    if (control) control(r, operator_of(client, *user), audit);
    if (r.kind != K::drive && r.kind != K::stop)
      send_to(h, {{"channel", "WEB_CONTROL"}, {"ok", true}, {"request", describe_request(r)}});
  }

  void on_open(Hdl h) {
    if (stopping) return;
    auto& client = clients[h];
    {
      std::error_code ec;
      auto con = server.get_con_from_hdl(h, ec);
      if (!ec) {
        client.token = session_cookie_value(con->get_request_header("Cookie"));
        client.address = peer_address(con);
      }
    }
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
    send_lease();
  }

  void forget(Hdl h) {
    const auto it = clients.find(h);
    if (it == clients.end()) return;
    if (is_holder(h)) drop_lease("the operator's page disconnected");
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
    // With TLS: also every plain-HTTP request and every client that does not
    // trust the certificate ("TLS handshake failed").
    if (!ec && !stopping) log("connection from " + peer_address(con) + " failed: " + con->get_ec().message());
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

  void broadcast(const std::string& key, const std::string& payload, bool keep) override {
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

  void shutdown() override {
    if (stopping) return;
    if (holder) drop_lease("advee-web stops");
    stopping = true;
    login_pool.join();
    flush_timer.cancel();
    std::error_code ec;
    server.stop_listening(ec);
    for (auto& [hdl, client] : clients) {
      server.close(hdl, websocketpp::close::status::going_away, "advee-web stops", ec);
      dropped_closed += client.queue.dropped();
    }
    clients.clear();
  }

  BridgeStats stats() const override {
    BridgeStats s;
    s.clients = clients.size();
    s.messages = messages;
    s.dropped = dropped_closed;
    s.refused = refused;
    for (const auto& [hdl, client] : clients) s.dropped += client.queue.dropped();
    return s;
  }

  std::uint16_t port() const override {
    std::error_code ec;
    // get_local_endpoint is not const in websocketpp.
    const auto ep = const_cast<Server&>(server).get_local_endpoint(ec);
    return ec ? 0 : ep.port();
  }
};

BridgeServer::BridgeServer(asio::io_context& io, BridgeOptions options, Log log, Control control) {
  if (options.tls_cert.empty() != options.tls_key.empty())
    throw std::runtime_error("TLS needs both a certificate and a key");
  if (options.tls_cert.empty())
    impl_ = std::make_unique<ImplT<websocketpp::config::asio>>(io, std::move(options), std::move(log),
                                                                std::move(control));
  else
    impl_ = std::make_unique<ImplT<websocketpp::config::asio_tls>>(io, std::move(options), std::move(log),
                                                                    std::move(control));
  impl_->start();
}

BridgeServer::~BridgeServer() {
  if (impl_) impl_->shutdown();
}

void BridgeServer::broadcast(const std::string& key, const std::string& payload, bool keep) {
  impl_->broadcast(key, payload, keep);
}

void BridgeServer::shutdown() { impl_->shutdown(); }

BridgeStats BridgeServer::stats() const { return impl_->stats(); }

std::uint16_t BridgeServer::port() const { return impl_->port(); }

}  // namespace advee::web
