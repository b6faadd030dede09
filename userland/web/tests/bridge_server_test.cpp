// SPDX-License-Identifier: GPL-2.0
// The bridge over real sockets: the page's files over HTTP, messages over a
// WebSocket (handshake and frames by hand, as a browser sends them), the
// snapshot for a new client, and a client that does not read.
#include "advee/web/bridge_server.hpp"

#include <gtest/gtest.h>

#include <asio/connect.hpp>
#include <asio/ip/tcp.hpp>
#include <asio/post.hpp>
#include <asio/read.hpp>
#include <asio/write.hpp>
#include <cstdio>
#include <future>
#include <thread>

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
    server_.emplace(io_, opt, [](const std::string&) {});
    work_.emplace(asio::make_work_guard(io_));
    thread_ = std::jthread([this] { io_.run(); });
  }
  void TearDown() override {
    on_io([this] { server_->shutdown(); });
    work_.reset();
    io_.stop();
    thread_.join();
    server_.reset();
  }
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
  tcp::socket websocket() {
    auto s = connect();
    asio::write(s, asio::buffer(std::string(
                       "GET / HTTP/1.1\r\nHost: x\r\nUpgrade: websocket\r\nConnection: Upgrade\r\n"
                       "Sec-WebSocket-Key: dGhlIHNhbXBsZSBub25jZQ==\r\nSec-WebSocket-Version: 13\r\n\r\n")));
    // Byte by byte: the first frames may follow the headers at once.
    std::string head;
    while (head.size() < 4 || head.compare(head.size() - 4, 4, "\r\n\r\n") != 0) {
      char c;
      asio::read(s, asio::buffer(&c, 1));
      head.push_back(c);
    }
    EXPECT_EQ(head.rfind("HTTP/1.1 101", 0), 0u) << head;
    return s;
  }
  // One unmasked server frame's text.
  static std::string read_frame(tcp::socket& s) {
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
  // Frames until one whose text starts with `prefix` (skips WEB_BRIDGE status).
  static std::string read_until_prefix(tcp::socket& s, const std::string& prefix) {
    for (;;) {
      auto f = read_frame(s);
      if (f.rfind(prefix, 0) == 0) return f;
    }
  }

  asio::io_context io_, client_io_;
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

}  // namespace
}  // namespace advee::web
