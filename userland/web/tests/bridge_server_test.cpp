// SPDX-License-Identifier: GPL-2.0
// The bridge over real sockets: the page's files over HTTP, messages over a
// WebSocket (handshake and frames by hand, as a browser sends them), the
// snapshot for a new client, and a client that does not read; login, the
// Origin check, the control lease and the stops the bridge sends itself.
#include "advee/web/bridge_server.hpp"

#include <gtest/gtest.h>

#include <asio/connect.hpp>
#include <asio/ip/tcp.hpp>
#include <asio/post.hpp>
#include <asio/read.hpp>
#include <asio/write.hpp>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <future>
#include <mutex>
#include <thread>
#include <vector>

#include "advee/web/password_file.hpp"
#include "websocket_test_client.hpp"

namespace advee::web {
namespace {

using asio::ip::tcp;

class Bridge : public ::testing::Test {
 protected:
  void SetUp() override {
    BridgeOptions opt;
    opt.port = 0;
    opt.root = ADVEE_WEB_STATIC_DIR;
    opt.scene_json = R"({"robot":{"wheelbase_m":0.62}})";
    opt.max_buffered_bytes = 64 * 1024;
    opt.flush_interval_ms = 20;
    init_crypto();
    char tmpl[] = "/tmp/advee-web-bridge-XXXXXX";
    ASSERT_NE(::mkdtemp(tmpl), nullptr);
    dir_ = tmpl;
    PasswordFile operators;
    operators.set("alice", "alice-password");
    operators.set("bob", "bob-password");
    operators.save(dir_ / "operators");
    opt.password_file = dir_ / "operators";
    opt.drive_limits = {0.5, 0.5};
    opt.drive_timeout_ms = 60000;  // a test that wants it sets it
    configure(opt);
    server_.emplace(io_, opt, [](const std::string& s) { if (std::getenv("WEB_TEST_LOG")) std::fprintf(stderr, "log: %s\n", s.c_str()); },
                    [this](const ControlRequest& r, const Operator& who, bool audit) {
                      std::lock_guard lock(mutex_);
                      control_.push_back({r, who, audit});
                    });
    work_.emplace(asio::make_work_guard(io_));
    thread_ = std::jthread([this] { io_.run(); });
  }
  void TearDown() override {
    on_io([this] { server_->shutdown(); });
    work_.reset();
    io_.stop();
    thread_.join();
    server_.reset();
    std::filesystem::remove_all(dir_);
  }
  virtual void configure(BridgeOptions&) {}
  // Runs f on the server's thread and waits for it.
  template <typename F>
  void on_io(F f) {
    std::promise<void> done;
    asio::post(io_, [&] {
      f();
      done.set_value();
    });
    done.get_future().wait();
  }
  void broadcast(const std::string& key, const std::string& payload, bool keep = false) {
    on_io([&] { server_->broadcast(key, payload, keep); });
  }
  BridgeStats stats() {
    BridgeStats s;
    on_io([&] { s = server_->stats(); });
    return s;
  }

  tcp::socket connect() {
    tcp::socket s(client_io_);
    s.connect(tcp::endpoint(asio::ip::make_address("127.0.0.1"), server_->port()));
    return s;
  }
  // Status line + headers + body of one HTTP/1.1 GET.
  std::string http_get(const std::string& target) {
    auto s = connect();
    asio::write(s, asio::buffer("GET " + target + " HTTP/1.1\r\nHost: x\r\nConnection: close\r\n\r\n"));
    std::string out;
    std::error_code ec;
    asio::read(s, asio::dynamic_buffer(out), ec);  // until the server closes
    return out;
  }
  // Status line + headers + body of one HTTP/1.1 POST.
  std::string http_post(const std::string& target, const std::string& body, const std::string& headers) {
    auto s = connect();
    asio::write(s, asio::buffer("POST " + target + " HTTP/1.1\r\nHost: x\r\nConnection: close\r\n" + headers +
                                "Content-Type: application/json\r\nContent-Length: " + std::to_string(body.size()) +
                                "\r\n\r\n" + body));
    std::string out;
    std::error_code ec;
    asio::read(s, asio::dynamic_buffer(out), ec);
    return out;
  }
  // The session cookie of a successful login ("" when refused).
  std::string login(const std::string& user, const std::string& password) {
    const auto r = http_post("/login", R"({"user":")" + user + R"(","password":")" + password + R"("})",
                             "Origin: http://x\r\n");
    const auto at = r.find("advee_session=");
    if (r.rfind("HTTP/1.1 200", 0) != 0 || at == std::string::npos) return "";
    return r.substr(at + 14, 64);
  }
  // The upgrade's answer head; `s` is left open after a 101.
  static std::string upgrade(tcp::socket& s, const std::string& headers) {
    return test::websocket_upgrade(s, "x", headers);
  }
  tcp::socket websocket(const std::string& cookie = "") {
    auto s = connect();
    const auto head =
        upgrade(s, "Origin: http://x\r\n" + (cookie.empty() ? "" : "Cookie: advee_session=" + cookie + "\r\n"));
    EXPECT_EQ(head.rfind("HTTP/1.1 101", 0), 0u) << head;
    return s;
  }
  static void send_frame(tcp::socket& s, const std::string& payload, std::uint8_t opcode = 1) {
    test::websocket_send(s, payload, opcode);
  }
  struct Call {
    ControlRequest request;
    Operator who;
    bool audit;
  };
  std::vector<Call> calls() {
    std::vector<Call> c;
    on_io([&] {
      std::lock_guard lock(mutex_);
      c = control_;
    });
    return c;
  }
  // Waits (up to 5 s) until the control sink has had `n` calls.
  std::vector<Call> wait_calls(std::size_t n) {
    const auto end = std::chrono::steady_clock::now() + std::chrono::seconds(5);
    auto c = calls();
    while (c.size() < n && std::chrono::steady_clock::now() < end) {
      std::this_thread::sleep_for(std::chrono::milliseconds(5));
      c = calls();
    }
    return c;
  }
  static std::string read_frame(tcp::socket& s) { return test::websocket_read(s); }
  static std::string read_until_prefix(tcp::socket& s, const std::string& prefix) {
    return test::websocket_read_until(s, prefix);
  }

  asio::io_context io_, client_io_;
  std::filesystem::path dir_;
  std::mutex mutex_;
  std::vector<Call> control_;
  std::optional<BridgeServer> server_;
  std::optional<asio::executor_work_guard<asio::io_context::executor_type>> work_;
  std::jthread thread_;
};

TEST_F(Bridge, ServesThePageAndTheScene) {
  const auto index = http_get("/");
  EXPECT_EQ(index.rfind("HTTP/1.1 200", 0), 0u) << index.substr(0, 200);
  EXPECT_NE(index.find("text/html"), std::string::npos);
  EXPECT_NE(index.find("dashboard.js"), std::string::npos);
  const auto scene = http_get("/scene.json");
  EXPECT_EQ(scene.rfind("HTTP/1.1 200", 0), 0u);
  EXPECT_NE(scene.find(R"({"robot":{"wheelbase_m":0.62}})"), std::string::npos);
  EXPECT_EQ(http_get("/../CMakeLists.txt").rfind("HTTP/1.1 404", 0), 0u);
  EXPECT_EQ(http_get("/missing.js").rfind("HTTP/1.1 404", 0), 0u);
}

TEST_F(Bridge, NoHistoryNoHistoryFrame) {
  broadcast("CM_DATA_STATE/a", R"({"channel":"CM_DATA_STATE","module":"a"})");
  auto s = websocket();
  EXPECT_EQ(read_frame(s), R"({"channel":"CM_DATA_STATE","module":"a"})");
}

TEST_F(Bridge, PushesMessagesToEveryClient) {
  auto a = websocket();
  auto b = websocket();
  // Both connections are registered once the server has answered them; the
  // open handler has run on the io thread before the 101 reached us.
  broadcast("LL_DATA_ODO", R"({"channel":"LL_DATA_ODO","n":1})");
  EXPECT_EQ(read_until_prefix(a, R"({"channel":"LL_DATA_ODO")"), R"({"channel":"LL_DATA_ODO","n":1})");
  EXPECT_EQ(read_until_prefix(b, R"({"channel":"LL_DATA_ODO")"), R"({"channel":"LL_DATA_ODO","n":1})");
  EXPECT_EQ(stats().clients, 2u);
}

TEST_F(Bridge, NewClientGetsTheNewestOfEachKeyFirst) {
  broadcast("CM_DATA_STATE/a", R"({"channel":"CM_DATA_STATE","module":"a","state":1})");
  broadcast("CM_DATA_STATE/b", R"({"channel":"CM_DATA_STATE","module":"b","state":3})");
  broadcast("CM_DATA_STATE/a", R"({"channel":"CM_DATA_STATE","module":"a","state":3})");
  auto s = websocket();
  EXPECT_EQ(read_until_prefix(s, R"({"channel":"CM_DATA_STATE")"),
            R"({"channel":"CM_DATA_STATE","module":"a","state":3})");
  EXPECT_EQ(read_until_prefix(s, R"({"channel":"CM_DATA_STATE")"),
            R"({"channel":"CM_DATA_STATE","module":"b","state":3})");
}

TEST_F(Bridge, NewClientGetsTheSnapshotThenTheHistoryInOneFrame) {
  for (int i = 0; i < 5; ++i)
    broadcast("WEB_ODO_POSE", R"({"channel":"WEB_ODO_POSE","i":)" + std::to_string(i) + "}", true);
  broadcast("CM_DATA_STATE/a", R"({"channel":"CM_DATA_STATE","module":"a"})");  // not kept
  auto s = websocket();
  // The snapshot: the newest per key, in key order; the bridge's status.
  EXPECT_EQ(read_frame(s), R"({"channel":"CM_DATA_STATE","module":"a"})");
  EXPECT_EQ(read_frame(s), R"({"channel":"WEB_ODO_POSE","i":4})");
  EXPECT_EQ(read_frame(s).rfind(R"({"channel":"WEB_BRIDGE")", 0), 0u);
  // Then the history, oldest first, in one frame.
  EXPECT_EQ(read_frame(s),
            R"({"channel":"WEB_HISTORY","messages":[{"channel":"WEB_ODO_POSE","i":0},)"
            R"({"channel":"WEB_ODO_POSE","i":1},{"channel":"WEB_ODO_POSE","i":2},)"
            R"({"channel":"WEB_ODO_POSE","i":3},{"channel":"WEB_ODO_POSE","i":4}]})");
}

TEST_F(Bridge, SlowClientGetsTheNewestAndDropsAreCounted) {
  auto slow = websocket();
  const std::string filler(64 * 1024, 'x');
  const int sent = 500;  // 32 MiB in total: far more than the sockets hold
  for (int i = 0; i < sent; ++i)
    broadcast("LL_DATA_SRFS", R"({"channel":"LL_DATA_SRFS","i":)" + std::to_string(i) +
                                  R"(,"f":")" + filler + "\"}");
  const auto st = stats();
  EXPECT_GT(st.dropped, 0u);
  // Now read: the stream ends with the newest message, and most never came.
  int received = 0;
  std::string last;
  const std::string want_last = R"({"channel":"LL_DATA_SRFS","i":)" + std::to_string(sent - 1) + ",";
  while (last.rfind(want_last, 0) != 0) {
    last = read_until_prefix(slow, R"({"channel":"LL_DATA_SRFS")");
    ++received;
  }
  EXPECT_LT(received, sent / 2);
  std::printf("slow client: %d of %d received\n", received, sent);
  EXPECT_EQ(static_cast<std::uint64_t>(received) + stats().dropped, static_cast<std::uint64_t>(sent));
}


TEST_F(Bridge, WebSocketNeedsThePagesOwnOrigin) {
  for (const char* h : {"", "Origin: http://evil.example\r\n", "Origin: null\r\n"}) {
    auto s = connect();
    const auto head = upgrade(s, h);
    EXPECT_EQ(head.rfind("HTTP/1.1 403", 0), 0u) << h << head;
  }
  EXPECT_EQ(stats().clients, 0u);
}

TEST_F(Bridge, LoginSetsAStrictHttpOnlyCookieAndWrongPasswordsAreRefused) {
  const auto ok = http_post("/login", R"({"user":"alice","password":"alice-password"})", "Origin: http://x\r\n");
  EXPECT_EQ(ok.rfind("HTTP/1.1 200", 0), 0u) << ok;
  EXPECT_NE(ok.find("Set-Cookie: advee_session="), std::string::npos);
  EXPECT_NE(ok.find("; Path=/; HttpOnly; SameSite=Strict"), std::string::npos);
  EXPECT_EQ(http_post("/login", R"({"user":"alice","password":"wrong"})", "Origin: http://x\r\n").rfind("HTTP/1.1 401", 0), 0u);
  EXPECT_EQ(http_post("/login", R"({"user":"mallory","password":"alice-password"})", "Origin: http://x\r\n")
                .rfind("HTTP/1.1 401", 0), 0u);
  EXPECT_EQ(http_post("/login", R"({"user":"alice","password":"alice-password"})", "Origin: http://evil\r\n")
                .rfind("HTTP/1.1 403", 0), 0u);
  EXPECT_EQ(http_post("/login", "not json", "Origin: http://x\r\n").rfind("HTTP/1.1 400", 0), 0u);
}

TEST_F(Bridge, FailedLoginsAreRateLimited) {
  for (int i = 0; i < 5; ++i) EXPECT_EQ(login("alice", "guess" + std::to_string(i)), "");
  const auto r = http_post("/login", R"({"user":"alice","password":"alice-password"})", "Origin: http://x\r\n");
  EXPECT_EQ(r.rfind("HTTP/1.1 429", 0), 0u) << r;  // even the right password: the address waits
  EXPECT_NE(r.find("Retry-After: "), std::string::npos);
}

TEST_F(Bridge, ControlNeedsALoginAndTheLeaseThenDisconnectStops) {
  auto viewer = websocket();  // no cookie: sees, cannot control
  send_frame(viewer, R"({"type":"take"})");
  send_frame(viewer, R"({"type":"drive","speed_mps":0.2,"steering_rad":0})");
  EXPECT_NE(read_until_prefix(viewer, R"({"channel":"WEB_CONTROL")").find("login required"), std::string::npos);
  auto forged = websocket(std::string(64, 'a'));
  send_frame(forged, R"({"type":"take"})");
  EXPECT_NE(read_until_prefix(forged, R"({"channel":"WEB_CONTROL")").find("login required"), std::string::npos);

  const auto cookie = login("alice", "alice-password");
  ASSERT_EQ(cookie.size(), 64u);
  {
    auto op = websocket(cookie);
    send_frame(op, R"({"type":"drive","speed_mps":0.2,"steering_rad":0})");
    EXPECT_NE(read_until_prefix(op, R"({"channel":"WEB_CONTROL")").find("take control first"), std::string::npos);
    EXPECT_EQ(calls().size(), 0u);
    send_frame(op, R"({"type":"take"})");
    EXPECT_NE(read_until_prefix(op, R"({"channel":"WEB_LEASE","holder":"alice")").find(R"("you":true)"),
              std::string::npos);
    send_frame(op, R"({"type":"drive","speed_mps":0.2,"steering_rad":-0.1})");
    auto c = wait_calls(2);
    ASSERT_EQ(c.size(), 2u);
    EXPECT_EQ(c[0].request.kind, ControlRequest::Kind::take);
    EXPECT_EQ(c[1].request.kind, ControlRequest::Kind::drive);
    EXPECT_DOUBLE_EQ(c[1].request.speed_mps, 0.2);
    EXPECT_DOUBLE_EQ(c[1].request.steering_rad, -0.1);
    EXPECT_EQ(c[1].who.name, "alice");
    EXPECT_EQ(c[1].who.address, "127.0.0.1");
    EXPECT_TRUE(c[1].audit);  // driving starts: logged
    send_frame(op, R"({"type":"drive","speed_mps":0.3,"steering_rad":-0.1})");
    c = wait_calls(3);
    ASSERT_EQ(c.size(), 3u);
    EXPECT_FALSE(c[2].audit);  // not every command
    // The viewer still cannot, while alice holds the lease.
    send_frame(viewer, R"({"type":"stop"})");
    read_until_prefix(viewer, R"({"channel":"WEB_CONTROL")");
  }  // the operator's socket closes: the bridge stops the robot
  const auto c = wait_calls(4);
  ASSERT_EQ(c.size(), 4u);
  EXPECT_EQ(c[3].request.kind, ControlRequest::Kind::stop);
  EXPECT_EQ(c[3].request.cause, "the operator's page disconnected");
  EXPECT_TRUE(c[3].audit);
  EXPECT_NE(read_until_prefix(viewer, R"({"channel":"WEB_LEASE")").find(R"("holder":null)"), std::string::npos);
}

TEST_F(Bridge, LogoutEndsControl) {
  const auto cookie = login("alice", "alice-password");
  auto op = websocket(cookie);
  send_frame(op, R"({"type":"take"})");
  read_until_prefix(op, R"({"channel":"WEB_LEASE","holder":"alice")");
  EXPECT_EQ(http_post("/logout", "", "Origin: http://x\r\nCookie: advee_session=" + cookie + "\r\n").rfind("HTTP/1.1 200", 0), 0u);
  EXPECT_NE(read_until_prefix(op, R"({"channel":"WEB_LEASE")").find(R"("holder":null)"), std::string::npos);
  send_frame(op, R"({"type":"take"})");
  send_frame(op, R"({"type":"drive","speed_mps":0.2,"steering_rad":0})");
  EXPECT_NE(read_until_prefix(op, R"({"channel":"WEB_CONTROL")").find("login required"), std::string::npos);
  const auto c = calls();
  ASSERT_EQ(c.size(), 2u);  // take, and the stop of the logout
  EXPECT_EQ(c[1].request.kind, ControlRequest::Kind::stop);
  EXPECT_EQ(c[1].request.cause, "logged out");
}

TEST_F(Bridge, ASecondOperatorTakesOverExplicitlyAndTheFirstIsTold) {
  auto a = websocket(login("alice", "alice-password"));
  auto b = websocket(login("bob", "bob-password"));
  send_frame(a, R"({"type":"take"})");
  read_until_prefix(a, R"({"channel":"WEB_LEASE","holder":"alice")");
  send_frame(a, R"({"type":"drive","speed_mps":0.2,"steering_rad":0})");
  send_frame(b, R"({"type":"take"})");
  EXPECT_NE(read_until_prefix(b, R"({"channel":"WEB_CONTROL")").find("control is held by alice"), std::string::npos);
  send_frame(b, R"({"type":"take","force":true})");
  EXPECT_EQ(read_until_prefix(a, R"({"channel":"WEB_LEASE","holder":"bob")"),
            R"({"channel":"WEB_LEASE","holder":"bob","you":false,"event":"taken","by":"bob"})");
  const auto c = wait_calls(4);
  ASSERT_EQ(c.size(), 4u);  // take, drive, the stop for alice, bob's take
  EXPECT_EQ(c[2].request.kind, ControlRequest::Kind::stop);
  EXPECT_EQ(c[2].who.name, "alice");
  EXPECT_EQ(c[2].request.cause, "taken over by bob");
  EXPECT_EQ(describe_request(c[2].request), "stop by the bridge: taken over by bob");
  EXPECT_EQ(c[3].who.name, "bob");
}

TEST_F(Bridge, MalformedAndOversizedMessagesNeverReachTheControlAndTheBridgeStays) {
  const auto cookie = login("alice", "alice-password");
  auto op = websocket(cookie);
  send_frame(op, R"({"type":"take"})");
  read_until_prefix(op, R"({"channel":"WEB_LEASE","holder":"alice")");
  const std::string bad[] = {"", "{", "[]", "null", R"({"type":"drive","speed_mps":9,"steering_rad":0})",
                             R"({"type":"drive","speed_mps":"0.1","steering_rad":0})",
                             R"({"type":"power","action":"reboot"})", std::string(2000, '{')};
  for (int i = 0; i < 100; ++i) send_frame(op, bad[i % std::size(bad)]);
  send_frame(op, R"({"type":"drive","speed_mps":0.1,"steering_rad":0})", 2);  // binary
  for (int i = 0; i < 101; ++i) read_until_prefix(op, R"({"channel":"WEB_CONTROL","ok":false)");
  EXPECT_EQ(calls().size(), 1u);  // the take only
  EXPECT_EQ(stats().refused, 101u);
  // A text frame that is not UTF-8: websocketpp closes the connection (1007);
  // the holder's stop is sent.
  send_frame(op, "\x80\xff");
  auto c = wait_calls(2);
  ASSERT_EQ(c.size(), 2u);
  EXPECT_EQ(c[1].request.kind, ControlRequest::Kind::stop);
  // Over the frame limit: the connection is closed (1009), the stop sent.
  auto op2 = websocket(cookie);
  send_frame(op2, R"({"type":"take"})");
  read_until_prefix(op2, R"({"channel":"WEB_LEASE","holder":"alice")");
  send_frame(op2, std::string(64 * 1024 + 1, ' '));
  c = wait_calls(4);
  ASSERT_EQ(c.size(), 4u);
  EXPECT_EQ(c[3].request.kind, ControlRequest::Kind::stop);
  auto again = websocket();  // still serving
  EXPECT_EQ(http_get("/").rfind("HTTP/1.1 200", 0), 0u);
}

class BridgeDriveTimeout : public Bridge {
  void configure(BridgeOptions& o) override { o.drive_timeout_ms = 200; }
};

TEST_F(BridgeDriveTimeout, DriveCommandsThatStopComingStopTheRobot) {
  auto op = websocket(login("alice", "alice-password"));
  send_frame(op, R"({"type":"take"})");
  read_until_prefix(op, R"({"channel":"WEB_LEASE","holder":"alice")");
  const auto t0 = std::chrono::steady_clock::now();
  send_frame(op, R"({"type":"drive","speed_mps":0.2,"steering_rad":0})");
  const auto c = wait_calls(3);
  const double ms = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
  ASSERT_EQ(c.size(), 3u);
  EXPECT_EQ(c[2].request.kind, ControlRequest::Kind::stop);
  EXPECT_EQ(c[2].request.cause, "no drive command for 200 ms");
  EXPECT_GE(ms, 200);
  std::printf("stop after the last drive command: %.0f ms (timeout 200 ms, flush every 20 ms)\n", ms);
}


class BridgeViewLogin : public Bridge {
  void configure(BridgeOptions& o) override { o.view_requires_login = true; }
};

TEST_F(BridgeViewLogin, TheLiveViewNeedsALoginToo) {
  auto anon = connect();
  EXPECT_EQ(upgrade(anon, "Origin: http://x\r\n").rfind("HTTP/1.1 401", 0), 0u);
  auto forged = connect();
  EXPECT_EQ(upgrade(forged, "Origin: http://x\r\nCookie: advee_session=" + std::string(64, 'b') + "\r\n")
                .rfind("HTTP/1.1 401", 0), 0u);
  EXPECT_EQ(http_get("/").rfind("HTTP/1.1 200", 0), 0u);  // the page itself holds no data
  auto op = websocket(login("alice", "alice-password"));
  broadcast("LL_DATA_ODO", R"({"channel":"LL_DATA_ODO","n":1})");
  EXPECT_EQ(read_until_prefix(op, R"({"channel":"LL_DATA_ODO")"), R"({"channel":"LL_DATA_ODO","n":1})");
  EXPECT_EQ(stats().clients, 1u);
}

}  // namespace
}  // namespace advee::web
