// SPDX-License-Identifier: GPL-2.0
// advee-watchdog with real processes (advee-test-module) on LCM over UDP
// multicast on loopback, each test on its own port: a stopped module is
// restarted within 3 s (the requirement), a killed one at once, a
// crash loop backs off on the configured schedule, and CM_CMD_STATE PAUSE /
// RUN / TERMINATE is obeyed. Measured latencies are printed.
#include <gtest/gtest.h>
#include <signal.h>
#include <sys/socket.h>
#include <sys/un.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <functional>
#include <lcm/lcm-cpp.hpp>
#include <map>
#include <set>
#include <string>
#include <vector>

#include "advee/module/subscription.hpp"
#include "common/cmd_state_t.hpp"
#include "common/data_module_phase_t.hpp"
#include "common/data_state_t.hpp"

namespace {

using Clock = std::chrono::steady_clock;
using namespace std::chrono_literals;

double ms_between(Clock::time_point from, Clock::time_point to) {
  return std::chrono::duration<double, std::milli>(to - from).count();
}

struct Announce {
  Clock::time_point at;
  std::string module;
  int state;
  int pid;
};

class Supervised : public testing::Test {
 protected:
  void SetUp() override {
    // A port per test process keeps parallel tests (and other users of the
    // default group) apart.
    const int port = 20000 + ::getpid() % 20000;
    url_ = "udpm://239.255.76.67:" + std::to_string(port) + "?ttl=0";
    lcm_ = std::make_unique<lcm::LCM>(url_);
    ASSERT_TRUE(lcm_->good()) << "no LCM on " << url_ << " (multicast route on lo?)";
    state_sub_ = std::make_unique<advee::module::Subscription<common::data_state_t>>(
        *lcm_, "CM_DATA_STATE", [this](const common::data_state_t& m) { on_state(m); });
    phase_sub_ = std::make_unique<advee::module::Subscription<common::data_module_phase_t>>(
        *lcm_, "CM_DATA_MODULES", [this](const common::data_module_phase_t& m) { phases_.push_back(m); });
    dir_ = std::filesystem::temp_directory_path() /
           ("advee-watchdog-test-" + std::to_string(::getpid()));
    std::filesystem::create_directories(dir_);
  }

  void TearDown() override {
    if (wd_pid_ > 0) {
      ::kill(wd_pid_, SIGTERM);
      int st = 0;
      ::waitpid(wd_pid_, &st, 0);
      EXPECT_TRUE(WIFEXITED(st) && WEXITSTATUS(st) == 0) << "advee-watchdog status " << st;
      // Its modules went with it.
      for (int pid : seen_pids_) EXPECT_NE(::kill(pid, 0), 0) << "module pid " << pid << " survived";
    }
    std::filesystem::remove_all(dir_);
  }

  // modules: "name: args..." YAML flow lists for advee-test-module.
  void start(const std::map<std::string, std::string>& modules,
             const std::set<std::string>& kept_down = {},
             const std::map<std::string, std::string>& env = {}) {
    const auto cfg = dir_ / "watchdog.yaml";
    std::ofstream f(cfg);
    f << "module: {lcm_url: \"" << url_ << "\", print_severity: notice}\n"
      << "supervisor:\n  term_grace_s: 1\n"
      << "  backoff: {initial_s: 0.5, max_s: 4, factor: 2, stable_s: 2}\n"
      << "modules:\n";
    for (const auto& [name, args] : modules)
      f << "  - {name: " << name << ", path: " << ADVEE_TEST_MODULE_BIN << ", args: [" << name
        << (args.empty() ? "" : ", " + args) << "]"
        << (kept_down.count(name) ? ", start: false" : "") << "}\n";
    f.close();
    wd_pid_ = ::fork();
    ASSERT_GE(wd_pid_, 0);
    if (wd_pid_ == 0) {
      for (const auto& [k, v] : env) ::setenv(k.c_str(), v.c_str(), 1);
      ::execl(ADVEE_WATCHDOG_BIN, ADVEE_WATCHDOG_BIN, "--config", cfg.c_str(), nullptr);
      ::_exit(127);
    }
  }

  void on_state(const common::data_state_t& m) {
    states_.push_back({Clock::now(), m.module, m.state, m.pid});
    if (m.module != "watchdog") seen_pids_.insert(m.pid);
  }

  // Handles messages until pred() or the timeout; returns pred().
  bool wait_for(const std::function<bool()>& pred, std::chrono::milliseconds timeout) {
    const auto end = Clock::now() + timeout;
    while (!pred() && Clock::now() < end) lcm_->handleTimeout(20);
    return pred();
  }
  void spin(std::chrono::milliseconds d) {
    wait_for([] { return false; }, d);
  }

  // The newest announcement of `module` after index `from`, satisfying pred.
  const Announce* find_state(const std::string& module, std::size_t from,
                             const std::function<bool(const Announce&)>& pred) {
    for (std::size_t i = from; i < states_.size(); ++i)
      if (states_[i].module == module && pred(states_[i])) return &states_[i];
    return nullptr;
  }

  int running_pid(const std::string& module, std::chrono::milliseconds timeout = 8000ms) {
    const Announce* a = nullptr;
    wait_for([&] {
      return (a = find_state(module, 0, [](const Announce& s) {
                return s.state == common::data_state_t::RUN;
              })) != nullptr;
    }, timeout);
    return a ? a->pid : 0;
  }

  void command(const std::string& target, int state) {
    common::cmd_state_t c;
    c.utime = 0;
    c.module = "process_test";
    c.target = target;
    c.state = static_cast<std::int8_t>(state);
    c.manual = true;
    lcm_->publish("CM_CMD_STATE", &c);
  }

  std::string url_;
  std::unique_ptr<lcm::LCM> lcm_;
  std::unique_ptr<advee::module::Subscription<common::data_state_t>> state_sub_;
  std::unique_ptr<advee::module::Subscription<common::data_module_phase_t>> phase_sub_;
  std::filesystem::path dir_;
  pid_t wd_pid_ = -1;
  std::vector<Announce> states_;
  std::vector<common::data_module_phase_t> phases_;
  std::set<int> seen_pids_;
};

TEST_F(Supervised, StoppedModuleIsRestartedWithinThreeSeconds) {
  start({{"tmod", ""}});
  const int p1 = running_pid("tmod");
  ASSERT_GT(p1, 0);
  // Worst case: stop it right after an announcement (2 s until it counts as dead).
  const std::size_t mark = states_.size();
  ASSERT_TRUE(wait_for([&] { return find_state("tmod", mark, [](auto&) { return true; }); }, 2000ms));
  const auto t0 = Clock::now();
  ASSERT_EQ(::kill(p1, SIGSTOP), 0);
  const std::size_t after_stop = states_.size();
  const Announce* back = nullptr;
  wait_for([&] {
    return (back = find_state("tmod", after_stop, [&](const Announce& s) { return s.pid != p1; }));
  }, 6000ms);
  ASSERT_NE(back, nullptr) << "not restarted within 6 s";
  const double latency = ms_between(t0, back->at);
  std::printf("restart latency after SIGSTOP: %.0f ms\n", latency);
  RecordProperty("restart_after_stop_ms", static_cast<int>(latency));
  EXPECT_LT(latency, 3000.0);
  // The stopped instance is gone, not left behind stopped.
  EXPECT_TRUE(wait_for([&] { return ::kill(p1, 0) != 0; }, 2000ms));
}

TEST_F(Supervised, KilledModuleIsRestarted) {
  start({{"tmod", ""}});
  const int p1 = running_pid("tmod");
  ASSERT_GT(p1, 0);
  const std::size_t mark = states_.size();
  const auto t0 = Clock::now();
  ASSERT_EQ(::kill(p1, SIGKILL), 0);
  const Announce* back = nullptr;
  wait_for([&] {
    return (back = find_state("tmod", mark, [&](const Announce& s) { return s.pid != p1; }));
  }, 5000ms);
  ASSERT_NE(back, nullptr);
  const double latency = ms_between(t0, back->at);
  std::printf("restart latency after SIGKILL: %.0f ms\n", latency);
  RecordProperty("restart_after_kill_ms", static_cast<int>(latency));
  // The TERMINATED report carries the signal.
  bool reported = false;
  for (const auto& ph : phases_)
    reported |= ph.target == "tmod" && ph.phase == common::data_module_phase_t::TERMINATED &&
                ph.exit_status == 128 + SIGKILL;
  EXPECT_TRUE(reported);
}

TEST_F(Supervised, CrashLoopBacksOff) {
  // Exits with 0x41 200 ms after each start.
  start({{"crash", "--crash-after-ms, '200'"}});
  spin(9000ms);
  std::vector<int> delays;
  std::vector<Clock::time_point> starts;
  for (const auto& ph : phases_) {
    if (ph.target != "crash") continue;
    if (ph.phase == common::data_module_phase_t::TERMINATED) {
      EXPECT_EQ(ph.exit_status, 0x41);
      delays.push_back(ph.next_start_ms);
    }
  }
  // Start times from the first announcement of each new pid.
  std::set<int> pids;
  for (const auto& s : states_)
    if (s.module == "crash" && pids.insert(s.pid).second) starts.push_back(s.at);
  ASSERT_GE(delays.size(), 4u);
  // The announced schedule: 0 (first failure), then 0.5 s doubling, capped at 4 s.
  const std::vector<int> want{0, 500, 1000, 2000};
  for (std::size_t i = 0; i < want.size(); ++i)
    EXPECT_NEAR(delays[i], want[i], 30) << "delay " << i;
  ASSERT_GE(starts.size(), 4u);
  std::printf("crash loop: starts at");
  for (auto& t : starts) std::printf(" %.0f", ms_between(starts[0], t));
  std::printf(" ms\n");
  // Measured gaps between starts grow with the back-off.
  for (std::size_t i = 2; i < starts.size(); ++i)
    EXPECT_GT(starts[i] - starts[i - 1], starts[i - 1] - starts[i - 2]) << "start " << i;
  // In 9 s a module restarted without back-off would start ~20 times.
  EXPECT_LE(starts.size(), 6u);
}

TEST_F(Supervised, CommandsPauseRunTerminate) {
  start({{"tmod", ""}, {"other", ""}});
  const int p1 = running_pid("tmod");
  ASSERT_GT(p1, 0);
  ASSERT_GT(running_pid("other"), 0);

  std::size_t mark = states_.size();
  command("tmod", common::data_state_t::PAUSE);
  EXPECT_TRUE(wait_for([&] {
    return find_state("tmod", mark, [&](auto& s) { return s.state == common::data_state_t::PAUSE && s.pid == p1; });
  }, 2000ms));
  // Paused is alive: still the same process 3 s later, still announcing PAUSE.
  mark = states_.size();
  spin(3000ms);
  EXPECT_EQ(find_state("tmod", mark, [&](auto& s) { return s.pid != p1; }), nullptr);
  EXPECT_NE(find_state("tmod", mark, [&](auto& s) { return s.state == common::data_state_t::PAUSE; }), nullptr);

  mark = states_.size();
  command("tmod", common::data_state_t::RUN);
  EXPECT_TRUE(wait_for([&] {
    return find_state("tmod", mark, [&](auto& s) { return s.state == common::data_state_t::RUN && s.pid == p1; });
  }, 2000ms));

  command("tmod", common::data_state_t::TERMINATE);
  EXPECT_TRUE(wait_for([&] { return ::kill(p1, 0) != 0; }, 3000ms));
  // Kept down: nothing from tmod for 4 s (longer than dead_after + back-off),
  // while the other module keeps running.
  spin(500ms);
  mark = states_.size();
  spin(4000ms);
  EXPECT_EQ(find_state("tmod", mark, [](auto&) { return true; }), nullptr);
  EXPECT_NE(find_state("other", mark, [](auto&) { return true; }), nullptr);
  bool down = false;
  for (const auto& ph : phases_)
    down |= ph.target == "tmod" && ph.phase == common::data_module_phase_t::DOWN;
  EXPECT_TRUE(down);

  // RUN brings it back at once.
  mark = states_.size();
  const auto t0 = Clock::now();
  command("tmod", common::data_state_t::RUN);
  const Announce* back = nullptr;
  EXPECT_TRUE(wait_for([&] {
    return (back = find_state("tmod", mark, [&](auto& s) { return s.state == common::data_state_t::RUN && s.pid != p1; }));
  }, 3000ms));
  if (back) std::printf("start after RUN command: %.0f ms\n", ms_between(t0, back->at));
}

TEST_F(Supervised, StartFalseWaitsForRun) {
  start({{"tmod", ""}}, {"tmod"});
  // The supervisor announces itself like any module...
  ASSERT_TRUE(wait_for([&] {
    return find_state("watchdog", 0, [](auto& s) { return s.state == common::data_state_t::RUN; });
  }, 5000ms));
  // ...but leaves tmod down.
  spin(2500ms);
  EXPECT_EQ(find_state("tmod", 0, [](auto&) { return true; }), nullptr);
  command("tmod", common::data_state_t::RUN);
  EXPECT_GT(running_pid("tmod", 3000ms), 0);
}

// systemd's side of sd_notify: a datagram socket named in NOTIFY_SOCKET.
// READY=1 with a STATUS, WATCHDOG=1 pings at about half of WATCHDOG_USEC,
// STATUS updates when a module changes phase, and the module does not
// inherit the supervisor's notify socket.
TEST_F(Supervised, NotifiesSystemd) {
  const auto sock_path = dir_ / "notify.sock";
  const int fd = ::socket(AF_UNIX, SOCK_DGRAM | SOCK_CLOEXEC, 0);
  ASSERT_GE(fd, 0);
  sockaddr_un sa{};
  sa.sun_family = AF_UNIX;
  std::snprintf(sa.sun_path, sizeof sa.sun_path, "%s", sock_path.c_str());
  ASSERT_EQ(::bind(fd, reinterpret_cast<sockaddr*>(&sa), sizeof sa), 0);
  // 400 ms: pings expected about every 200 ms.
  start({{"tmod", ""}}, {}, {{"NOTIFY_SOCKET", sock_path.string()}, {"WATCHDOG_USEC", "400000"}});
  std::vector<std::pair<Clock::time_point, std::string>> got;
  const auto end = Clock::now() + 2500ms;
  while (Clock::now() < end) {
    lcm_->handleTimeout(10);  // keep the announcements flowing into states_
    char buf[512];
    const ssize_t n = ::recv(fd, buf, sizeof buf - 1, MSG_DONTWAIT);
    if (n > 0) got.emplace_back(Clock::now(), std::string(buf, static_cast<std::size_t>(n)));
  }
  ::close(fd);
  ASSERT_FALSE(got.empty()) << "nothing on NOTIFY_SOCKET";
  std::vector<Clock::time_point> pings;
  bool running_status = false, ready = false, ping_before_ready = false;
  for (const auto& [t, m] : got) {
    if (m == "WATCHDOG=1") {
      pings.push_back(t);
      ping_before_ready |= !ready;
    }
    ready |= m.rfind("READY=1\nSTATUS=", 0) == 0;
    running_status |= m == "STATUS=1/1 modules running";
  }
  EXPECT_TRUE(ready);
  EXPECT_FALSE(ping_before_ready);
  EXPECT_TRUE(running_status);
  // 2.5 s at one ping per 200 ms: about 12; well above the 6 that a ping
  // per WATCHDOG_USEC would give.
  std::printf("WATCHDOG=1 pings in 2.5 s with WATCHDOG_USEC=400000: %zu\n", pings.size());
  EXPECT_GE(pings.size(), 8u);
  for (std::size_t i = 1; i < pings.size(); ++i)
    EXPECT_LT(ms_between(pings[i - 1], pings[i]), 400.0) << "ping " << i;
  // The module announces, and does not talk to systemd itself.
  const Announce* a = find_state("tmod", 0, [](auto&) { return true; });
  ASSERT_NE(a, nullptr);
  std::ifstream environ("/proc/" + std::to_string(a->pid) + "/environ");
  std::string env((std::istreambuf_iterator<char>(environ)), std::istreambuf_iterator<char>());
  EXPECT_EQ(env.find("NOTIFY_SOCKET="), std::string::npos);
  EXPECT_NE(env.find("LCM_DEFAULT_URL=" + url_), std::string::npos);
}

}  // namespace
