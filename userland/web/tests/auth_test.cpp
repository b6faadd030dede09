// SPDX-License-Identifier: GPL-2.0
// Passwords, sessions, the login rate limit, the cookie and the Origin check.
#include <gtest/gtest.h>
#include <sys/stat.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <set>

#include "advee/web/http_auth.hpp"
#include "advee/web/login_limiter.hpp"
#include "advee/web/password_file.hpp"
#include "advee/web/session_store.hpp"

namespace advee::web {
namespace {

namespace fs = std::filesystem;
using namespace std::chrono_literals;

class Auth : public ::testing::Test {
 protected:
  void SetUp() override {
    init_crypto();
    char tmpl[] = "/tmp/advee-web-auth-XXXXXX";
    ASSERT_NE(::mkdtemp(tmpl), nullptr);
    dir_ = tmpl;
  }
  void TearDown() override { fs::remove_all(dir_); }
  fs::path dir_;
};

TEST_F(Auth, PasswordFileStoresOnlyASaltedHashReadableByOwnerAndGroup) {
  const auto path = dir_ / "operators";
  PasswordFile f = PasswordFile::load(path);  // missing = empty
  EXPECT_EQ(f.size(), 0u);
  f.set("alice", "correct horse");
  f.set("bob", "correct horse");
  f.save(path);
  struct stat st {};
  ASSERT_EQ(::stat(path.c_str(), &st), 0);
  EXPECT_EQ(st.st_mode & 0777, 0640u);
  std::ifstream in(path);
  const std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  EXPECT_EQ(text.find("correct horse"), std::string::npos);
  EXPECT_NE(text.find("alice:$argon2id$"), std::string::npos);
  const auto loaded = PasswordFile::load(path);
  EXPECT_TRUE(loaded.check("alice", "correct horse"));
  EXPECT_TRUE(loaded.check("bob", "correct horse"));
  EXPECT_FALSE(loaded.check("alice", "correct horse "));
  EXPECT_FALSE(loaded.check("alice", ""));
  EXPECT_FALSE(loaded.check("carol", "correct horse"));
  // Salted: the same password, two different hashes.
  const auto a = text.find("alice:"), b = text.find("bob:");
  EXPECT_NE(text.substr(a + 6, 40), text.substr(b + 4, 40));
}

TEST_F(Auth, PasswordFileRejectsMalformedLinesAndNames) {
  const auto path = dir_ / "operators";
  std::ofstream(path) << "# comment\nalice:plaintext\n";
  EXPECT_THROW(PasswordFile::load(path), std::runtime_error);
  PasswordFile f;
  EXPECT_THROW(f.set("a b", "x"), std::invalid_argument);
  EXPECT_THROW(f.set("", "x"), std::invalid_argument);
  EXPECT_THROW(f.set("a:b", "x"), std::invalid_argument);
  EXPECT_TRUE(valid_operator_name("ops.team-1_x"));
  EXPECT_FALSE(valid_operator_name(std::string(33, 'a')));
}

TEST_F(Auth, SessionsAreRandomExpireWhenIdleAndCanBeRevoked) {
  SessionStore store(60s, 3);
  const auto t0 = SessionStore::Clock::time_point{} + 1h;
  const auto a = store.create("alice", t0);
  const auto b = store.create("bob", t0);
  EXPECT_EQ(a.size(), 64u);
  EXPECT_NE(a, b);
  EXPECT_EQ(store.user(a, t0 + 59s).value_or(""), "alice");
  EXPECT_EQ(store.user(a, t0 + 118s).value_or(""), "alice");  // kept alive by use
  EXPECT_FALSE(store.user(b, t0 + 61s));                       // idle too long
  EXPECT_FALSE(store.user(b, t0 + 62s));
  std::string forged = a;
  forged[10] = forged[10] == '0' ? '1' : '0';
  EXPECT_FALSE(store.user(forged, t0 + 119s));
  EXPECT_FALSE(store.user("", t0 + 119s));
  EXPECT_FALSE(store.user(a + "0", t0 + 119s));
  store.revoke(a);
  EXPECT_FALSE(store.user(a, t0 + 120s));
  std::set<std::string> tokens;
  for (int i = 0; i < 10; ++i) tokens.insert(store.create("x", t0 + 121s));
  EXPECT_EQ(tokens.size(), 10u);
  EXPECT_EQ(store.size(), 3u);  // bounded
}

TEST_F(Auth, FailedLoginsAreLimitedPerAddress) {
  LoginLimiter lim(3, 60s, 2);
  const auto t0 = LoginLimiter::Clock::time_point{} + 1h;
  for (int i = 0; i < 3; ++i) {
    EXPECT_EQ(lim.retry_after("10.0.0.1", t0 + i * 1s), LoginLimiter::Clock::duration::zero());
    lim.failed("10.0.0.1", t0 + i * 1s);
  }
  EXPECT_EQ(lim.retry_after("10.0.0.1", t0 + 10s), 50s);  // until the first failure is 60 s old
  EXPECT_EQ(lim.retry_after("10.0.0.2", t0 + 10s), LoginLimiter::Clock::duration::zero());
  EXPECT_EQ(lim.retry_after("10.0.0.1", t0 + 60s), LoginLimiter::Clock::duration::zero());
  // A sliding window: the failures at 1 s and 2 s still count until 61 s and 62 s.
  lim.failed("10.0.0.1", t0 + 60s);
  EXPECT_EQ(lim.retry_after("10.0.0.1", t0 + 60s), 1s);
  lim.failed("10.0.0.1", t0 + 61s);
  EXPECT_EQ(lim.retry_after("10.0.0.1", t0 + 61s), 1s);
  lim.succeeded("10.0.0.1");
  EXPECT_EQ(lim.retry_after("10.0.0.1", t0 + 62s), LoginLimiter::Clock::duration::zero());
  for (int i = 0; i < 100; ++i) lim.failed("192.168.0." + std::to_string(i), t0 + 63s);
  EXPECT_LE(lim.addresses(), 2u);  // bounded
}

TEST(HttpAuth, Cookie) {
  EXPECT_EQ(session_cookie_value("a=1; advee_session=abc; b=2"), "abc");
  EXPECT_EQ(session_cookie_value("advee_session=abc"), "abc");
  EXPECT_EQ(session_cookie_value("xadvee_session=abc"), "");
  EXPECT_EQ(session_cookie_value(""), "");
  EXPECT_EQ(session_set_cookie("t", false), "advee_session=t; Path=/; HttpOnly; SameSite=Strict");
  EXPECT_EQ(session_set_cookie("t", true), "advee_session=t; Path=/; HttpOnly; SameSite=Strict; Secure");
  EXPECT_NE(session_clear_cookie(false).find("Max-Age=0"), std::string::npos);
}

TEST(HttpAuth, Origin) {
  EXPECT_TRUE(origin_allowed("http://robot:8080", "robot:8080", {}));
  EXPECT_TRUE(origin_allowed("https://robot:8443", "robot:8443", {}));
  EXPECT_FALSE(origin_allowed("http://evil:8080", "robot:8080", {}));
  EXPECT_FALSE(origin_allowed("http://robot:8081", "robot:8080", {}));
  EXPECT_FALSE(origin_allowed("", "robot:8080", {}));
  EXPECT_FALSE(origin_allowed("null", "robot:8080", {}));
  EXPECT_FALSE(origin_allowed("http://", "", {}));
  EXPECT_TRUE(origin_allowed("https://proxy", "robot:8080", {"https://proxy"}));
  // advee-web itself on TLS: only the https page of that host and port.
  EXPECT_TRUE(origin_allowed("https://robot:8443", "robot:8443", {}, true));
  EXPECT_FALSE(origin_allowed("http://robot:8443", "robot:8443", {}, true));
  EXPECT_TRUE(origin_allowed("http://proxy", "robot:8443", {"http://proxy"}, true));
}

}  // namespace
}  // namespace advee::web
