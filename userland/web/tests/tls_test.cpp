// SPDX-License-Identifier: GPL-2.0
// advee-web over TLS (--tls-cert, --tls-key) on loopback, with a throw-away
// self-signed certificate made by the openssl command for each test: HTTPS
// GET, login (the cookie gets Secure by itself), the WebSocket over TLS with
// the control protocol, the https-only Origin, plain HTTP to the TLS port
// refused without harm, and every bad certificate or key refused at start
// with a message naming the file (the program: exit 1, a lone --tls-cert 2).
#include "advee/web/bridge_server.hpp"

#include <gtest/gtest.h>
#include <sys/wait.h>
#include <unistd.h>

#include <asio/connect.hpp>
#include <asio/ip/tcp.hpp>
#include <asio/post.hpp>
#include <asio/read.hpp>
#include <asio/ssl.hpp>
#include <asio/write.hpp>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <future>
#include <mutex>
#include <sstream>
#include <thread>
#include <vector>

#include "advee/web/password_file.hpp"
#include "websocket_test_client.hpp"

namespace advee::web {
namespace {

using asio::ip::tcp;
using TlsStream = asio::ssl::stream<tcp::socket>;
namespace fs = std::filesystem;

// Runs a shell command; its exit status (-1 when it did not exit).
int run(const std::string& cmd) {
  const int st = std::system(cmd.c_str());
  return WIFEXITED(st) ? WEXITSTATUS(st) : -1;
}

// A fresh directory with a self-signed certificate for localhost and
// 127.0.0.1 (cert.pem, key.pem), a key of another certificate (other.pem),
// an encrypted key (encrypted.pem) and a file that is not PEM (junk.pem).
// EC P-256: made in milliseconds (an RSA key takes long under load).
class TlsFiles {
 public:
  TlsFiles() {
    char tmpl[] = "/tmp/advee-web-tls-XXXXXX";
    if (!::mkdtemp(tmpl)) throw std::runtime_error("mkdtemp");
    dir_ = tmpl;
    const std::string d = dir_.string();
    const std::string ec = " -newkey ec -pkeyopt ec_paramgen_curve:prime256v1 -nodes -days 2 ";
    ok_ = run("openssl req -x509" + ec + "-subj /CN=localhost -addext subjectAltName=DNS:localhost,IP:127.0.0.1 "
              "-keyout " + d + "/key.pem -out " + d + "/cert.pem 2>/dev/null") == 0 &&
          run("openssl genpkey -algorithm EC -pkeyopt ec_paramgen_curve:P-256 -out " + d +
              "/other.pem 2>/dev/null") == 0 &&
          run("openssl genpkey -algorithm EC -pkeyopt ec_paramgen_curve:P-256 -aes-128-cbc -pass pass:secret -out " +
              d + "/encrypted.pem 2>/dev/null") == 0;
    std::ofstream(dir_ / "junk.pem") << "not a certificate\n";
  }
  ~TlsFiles() { fs::remove_all(dir_); }
  TlsFiles(const TlsFiles&) = delete;
  TlsFiles& operator=(const TlsFiles&) = delete;
  bool ok() const { return ok_; }
  fs::path operator/(const char* name) const { return dir_ / name; }
  const fs::path& dir() const { return dir_; }

 private:
  fs::path dir_;
  bool ok_ = false;
};

class BridgeTls : public ::testing::Test {
 protected:
  void SetUp() override {
    ASSERT_TRUE(files_.ok()) << "the openssl command failed (package openssl)";
    BridgeOptions opt;
    opt.port = 0;
    opt.root = ADVEE_WEB_STATIC_DIR;
    opt.scene_json = R"({"robot":{"wheelbase_m":0.62}})";
    opt.flush_interval_ms = 20;
    opt.drive_limits = {0.5, 0.5};
    opt.drive_timeout_ms = 60000;
    opt.tls_cert = files_ / "cert.pem";
    opt.tls_key = files_ / "key.pem";
    init_crypto();
    PasswordFile operators;
    operators.set("alice", "alice-password");
    operators.save(files_ / "operators");
    opt.password_file = files_ / "operators";
    server_.emplace(io_, opt, [this](const std::string& s) {
      std::lock_guard lock(mutex_);
      log_.push_back(s);
    },
                    [this](const ControlRequest& r, const Operator& who, bool) {
                      std::lock_guard lock(mutex_);
                      control_.push_back({r, who});
                    });
    work_.emplace(asio::make_work_guard(io_));
    thread_ = std::jthread([this] { io_.run(); });
    // The client trusts exactly the test's certificate and checks the name.
    client_tls_.set_verify_mode(asio::ssl::verify_peer);
    client_tls_.load_verify_file((files_ / "cert.pem").string());
    client_tls_.set_verify_callback(asio::ssl::host_name_verification("localhost"));
  }
  void TearDown() override {
    if (!server_) return;
    on_io([this] { server_->shutdown(); });
    work_.reset();
    io_.stop();
    thread_.join();
    server_.reset();
  }
  template <typename F>
  void on_io(F f) {
    std::promise<void> done;
    asio::post(io_, [&] {
      f();
      done.set_value();
    });
    done.get_future().wait();
  }

  tcp::endpoint endpoint() const { return {asio::ip::make_address("127.0.0.1"), server_->port()}; }
  std::unique_ptr<TlsStream> connect() {
    auto s = std::make_unique<TlsStream>(client_io_, client_tls_);
    s->lowest_layer().connect(endpoint());
    s->handshake(asio::ssl::stream_base::client);
    return s;
  }
  // Status line + headers + body of one request (Connection: close).
  std::string request(const std::string& head, const std::string& body = "") {
    auto s = connect();
    asio::write(*s, asio::buffer(head + "Host: localhost\r\nConnection: close\r\n" +
                                 (body.empty() ? "" : "Content-Type: application/json\r\nContent-Length: " +
                                                          std::to_string(body.size()) + "\r\n") +
                                 "\r\n" + body));
    std::string out;
    std::error_code ec;
    asio::read(*s, asio::dynamic_buffer(out), ec);  // until the server closes
    return out;
  }
  std::string login(const std::string& origin) {
    return request("POST /login HTTP/1.1\r\nOrigin: " + origin + "\r\n",
                   R"({"user":"alice","password":"alice-password"})");
  }
  static std::string upgrade(TlsStream& s, const std::string& headers) {
    return test::websocket_upgrade(s, "localhost", headers);
  }
  static void send_frame(TlsStream& s, const std::string& payload) { test::websocket_send(s, payload); }
  static std::string read_frame(TlsStream& s) { return test::websocket_read(s); }
  static std::string read_until_prefix(TlsStream& s, const std::string& prefix) {
    return test::websocket_read_until(s, prefix);
  }
  std::vector<std::pair<ControlRequest, Operator>> wait_calls(std::size_t n) {
    const auto end = std::chrono::steady_clock::now() + std::chrono::seconds(5);
    for (;;) {
      std::vector<std::pair<ControlRequest, Operator>> c;
      on_io([&] {
        std::lock_guard lock(mutex_);
        c = control_;
      });
      if (c.size() >= n || std::chrono::steady_clock::now() > end) return c;
      std::this_thread::sleep_for(std::chrono::milliseconds(5));
    }
  }

  TlsFiles files_;
  asio::io_context io_, client_io_;
  asio::ssl::context client_tls_{asio::ssl::context::tls_client};
  std::mutex mutex_;
  std::vector<std::string> log_;
  std::vector<std::pair<ControlRequest, Operator>> control_;
  std::optional<BridgeServer> server_;
  std::optional<asio::executor_work_guard<asio::io_context::executor_type>> work_;
  std::jthread thread_;
};

TEST_F(BridgeTls, HttpsServesThePageWithTls12OrNewer) {
  auto s = connect();
  const std::string version = SSL_get_version(s->native_handle());
  EXPECT_TRUE(version == "TLSv1.2" || version == "TLSv1.3") << version;
  const auto index = request("GET / HTTP/1.1\r\n");
  EXPECT_EQ(index.rfind("HTTP/1.1 200", 0), 0u) << index.substr(0, 200);
  EXPECT_NE(index.find("dashboard.js"), std::string::npos);
  EXPECT_NE(request("GET /scene.json HTTP/1.1\r\n").find(R"({"robot":{"wheelbase_m":0.62}})"), std::string::npos);
}

TEST_F(BridgeTls, OldProtocolsAreRefused) {
  asio::ssl::context old{asio::ssl::context::tls_client};
  SSL_CTX_set_min_proto_version(old.native_handle(), TLS1_VERSION);
  SSL_CTX_set_max_proto_version(old.native_handle(), TLS1_1_VERSION);
  SSL_CTX_set_security_level(old.native_handle(), 0);  // OpenSSL 3 would not even offer 1.1 otherwise
  TlsStream s(client_io_, old);
  s.lowest_layer().connect(endpoint());
  std::error_code ec;
  s.handshake(asio::ssl::stream_base::client, ec);
  EXPECT_TRUE(ec) << "a TLS 1.1 handshake succeeded";
}

TEST_F(BridgeTls, LoginCookieIsSecureAndOnlyTheHttpsOriginCounts) {
  const auto r = login("https://localhost");
  EXPECT_EQ(r.rfind("HTTP/1.1 200", 0), 0u) << r;
  EXPECT_NE(r.find("advee_session="), std::string::npos);
  EXPECT_NE(r.find("; Secure"), std::string::npos) << r;
  const auto logout = request("POST /logout HTTP/1.1\r\nOrigin: https://localhost\r\n", "{}");
  EXPECT_NE(logout.find("; Secure; Max-Age=0"), std::string::npos) << logout;
  // http://localhost would be a page that this port never serves.
  EXPECT_EQ(login("http://localhost").rfind("HTTP/1.1 403", 0), 0u);
  auto s = connect();
  EXPECT_EQ(upgrade(*s, "Origin: http://localhost\r\n").rfind("HTTP/1.1 403", 0), 0u);
}

TEST_F(BridgeTls, TheControlProtocolWorksOverWss) {
  const auto r = login("https://localhost");
  const auto at = r.find("advee_session=");
  ASSERT_NE(at, std::string::npos) << r;
  const auto cookie = r.substr(at + 14, 64);
  auto s = connect();
  const auto head = upgrade(*s, "Origin: https://localhost\r\nCookie: advee_session=" + cookie + "\r\n");
  ASSERT_EQ(head.rfind("HTTP/1.1 101", 0), 0u) << head;
  on_io([this] { server_->broadcast("LL_DATA_ODO", R"({"channel":"LL_DATA_ODO","n":1})"); });
  EXPECT_EQ(read_until_prefix(*s, R"({"channel":"LL_DATA_ODO")"), R"({"channel":"LL_DATA_ODO","n":1})");
  send_frame(*s, R"({"type":"take"})");
  EXPECT_NE(read_until_prefix(*s, R"({"channel":"WEB_LEASE","holder":"alice")").find(R"("you":true)"),
            std::string::npos);
  send_frame(*s, R"({"type":"drive","speed_mps":0.2,"steering_rad":-0.1})");
  auto c = wait_calls(2);
  ASSERT_EQ(c.size(), 2u);
  EXPECT_EQ(c[1].first.kind, ControlRequest::Kind::drive);
  EXPECT_DOUBLE_EQ(c[1].first.speed_mps, 0.2);
  EXPECT_EQ(c[1].second.name, "alice");
  EXPECT_EQ(c[1].second.address, "127.0.0.1");  // the peer's address under TLS too
  send_frame(*s, R"({"type":"drive","speed_mps":9,"steering_rad":0})");
  EXPECT_NE(read_until_prefix(*s, R"({"channel":"WEB_CONTROL")").find(R"("ok":false)"), std::string::npos);
  s.reset();  // the TCP connection goes without a close: the bridge stops the robot
  c = wait_calls(3);
  ASSERT_EQ(c.size(), 3u);
  EXPECT_EQ(c[2].first.kind, ControlRequest::Kind::stop);
  EXPECT_EQ(c[2].first.cause, "the operator's page disconnected");
}

TEST_F(BridgeTls, PlainHttpToTheTlsPortIsRefusedAndTheServerStays) {
  for (int i = 0; i < 3; ++i) {
    tcp::socket s(client_io_);
    s.connect(endpoint());
    asio::write(s, asio::buffer(std::string("GET / HTTP/1.1\r\nHost: localhost\r\n\r\n")));
    std::string out;
    std::error_code ec;
    asio::read(s, asio::dynamic_buffer(out), ec);  // the server closes
    EXPECT_TRUE(ec == asio::error::eof || ec == asio::error::connection_reset) << ec.message();
    EXPECT_EQ(out.find("HTTP/"), std::string::npos) << "plain HTTP answered: " << out;
    // At most a TLS alert record (content type 21).
    if (!out.empty()) {
      EXPECT_EQ(static_cast<unsigned char>(out[0]), 21u);
    }
  }
  EXPECT_EQ(request("GET / HTTP/1.1\r\n").rfind("HTTP/1.1 200", 0), 0u);
  std::lock_guard lock(mutex_);
  bool logged = false;
  for (const auto& l : log_) logged = logged || l == "connection from 127.0.0.1 failed: TLS handshake failed";
  EXPECT_TRUE(logged);
}

// The server constructor alone: each bad file is refused with its name.
class TlsFilesRefused : public ::testing::Test {
 protected:
  std::string error_of(const fs::path& cert, const fs::path& key) {
    BridgeOptions opt;
    opt.port = 0;
    opt.root = ADVEE_WEB_STATIC_DIR;
    opt.tls_cert = cert;
    opt.tls_key = key;
    asio::io_context io;
    try {
      BridgeServer server(io, opt, [](const std::string&) {});
    } catch (const std::runtime_error& e) {
      return e.what();
    }
    return "";
  }
  TlsFiles files_;
};

TEST_F(TlsFilesRefused, EachBadFileIsNamed) {
  ASSERT_TRUE(files_.ok());
  const auto cert = files_ / "cert.pem", key = files_ / "key.pem";
  EXPECT_EQ(error_of(cert, key), "");  // the good pair starts
  EXPECT_EQ(error_of(files_ / "missing.pem", key),
            "TLS certificate " + (files_ / "missing.pem").string() + ": No such file or directory");
  EXPECT_EQ(error_of(cert, files_ / "missing.pem"),
            "TLS key " + (files_ / "missing.pem").string() + ": No such file or directory");
  EXPECT_EQ(error_of(files_ / "junk.pem", key).rfind("TLS certificate " + (files_ / "junk.pem").string() +
                                                         ": not a PEM certificate",
                                                     0),
            0u);
  EXPECT_EQ(error_of(cert, files_ / "junk.pem").rfind("TLS key " + (files_ / "junk.pem").string(), 0), 0u);
  // Encrypted: refused at once, no passphrase prompt on the terminal.
  EXPECT_EQ(error_of(cert, files_ / "encrypted.pem").rfind("TLS key " + (files_ / "encrypted.pem").string() +
                                                                ": not an unencrypted PEM private key",
                                                            0),
            0u);
  EXPECT_EQ(error_of(cert, files_ / "other.pem").rfind("TLS key " + (files_ / "other.pem").string() +
                                                            " does not belong to the certificate",
                                                        0),
            0u);
  EXPECT_EQ(error_of(key, cert).rfind("TLS certificate " + key.string() + ": not a PEM certificate", 0), 0u);
  EXPECT_EQ(error_of(cert, ""), "TLS needs both a certificate and a key");
  if (::geteuid() != 0) {  // root reads any file
    fs::permissions(key, fs::perms::none);
    EXPECT_EQ(error_of(cert, key), "TLS key " + key.string() + ": Permission denied");
  }
}

// The program: a bad file is exit 1 with the message, a lone option exit 2.
TEST_F(TlsFilesRefused, TheProgramExitsWithTheDocumentedCodes) {
  ASSERT_TRUE(files_.ok());
  const std::string base = std::string(ADVEE_WEB_PROGRAM) + " --root " + ADVEE_WEB_STATIC_DIR +
                           " --lcm memq:// --robot '' --map '' --listen 127.0.0.1:0 --operators " +
                           (files_ / "operators").string();
  const auto err = (files_ / "stderr").string();
  auto stderr_text = [&] {
    std::stringstream ss;
    ss << std::ifstream(err).rdbuf();
    return ss.str();
  };
  EXPECT_EQ(run(base + " --tls-cert " + (files_ / "missing.pem").string() + " --tls-key " +
                (files_ / "key.pem").string() + " 2>" + err),
            1);
  EXPECT_NE(stderr_text().find("advee-web: TLS certificate " + (files_ / "missing.pem").string() +
                               ": No such file or directory"),
            std::string::npos)
      << stderr_text();
  EXPECT_EQ(run(base + " --tls-cert " + (files_ / "cert.pem").string() + " --tls-key " +
                (files_ / "other.pem").string() + " 2>" + err),
            1);
  EXPECT_NE(stderr_text().find("does not belong to the certificate"), std::string::npos) << stderr_text();
  EXPECT_EQ(run(base + " --tls-cert " + (files_ / "cert.pem").string() + " 2>" + err), 2);
  EXPECT_NE(stderr_text().find("--tls-key"), std::string::npos) << stderr_text();
}

}  // namespace
}  // namespace advee::web
