// SPDX-License-Identifier: GPL-2.0
// The supervisor's logic on a manual clock with fake processes and LCM's
// in-process provider: dead and startup deadlines, SIGTERM + SIGCONT then
// SIGKILL, restarts with back-off, commands, start: false, the shutdown and
// sd_notify. Time moves only in advance(), so every deadline is asserted
// exactly (to one check period) and the tests take no wall-clock time. The
// same behaviour with real processes: process_test.cpp (integration).
#include <gtest/gtest.h>
#include <poll.h>
#include <signal.h>
#include <sys/socket.h>
#include <sys/un.h>
#include <unistd.h>

#include <algorithm>
#include <cstdio>
#include <deque>
#include <filesystem>
#include <map>
#include <string>
#include <system_error>
#include <vector>

#include "advee/module/module.hpp"
#include "advee/module/subscription.hpp"
#include "advee/watchdog/process.hpp"
#include "advee/watchdog/supervisor.hpp"
#include "advee/watchdog/systemd_notify.hpp"
#include "common/cmd_state_t.hpp"
#include "common/data_module_phase_t.hpp"
#include "common/data_state_t.hpp"

using namespace advee;
using namespace advee::watchdog;
using namespace std::chrono_literals;
using module::ManualTimers;
using module::TimePoint;
using Phase_t = common::data_module_phase_t;

namespace {

long ms(module::Duration d) { return std::chrono::duration_cast<std::chrono::milliseconds>(d).count(); }

// Processes that exist only here. A child ends on SIGTERM (kept pending
// while it is stopped, delivered by SIGCONT) unless it ignores SIGTERM, and
// always on SIGKILL; an end queues its wait status for reap() and raises
// SIGCHLD, which the supervisor's Module reads from its signalfd as it would
// for a real child.
class FakeProcesses final : public Processes {
 public:
  struct Child {
    std::string name;
    std::map<std::string, std::string> env;
    TimePoint started;
    bool alive = true, stopped = false, ignores_term = false, term_pending = false;
    std::vector<std::pair<TimePoint, int>> signals;  // when, signo
  };

  explicit FakeProcesses(ManualTimers& clock) : clock_(clock) {}

  pid_t spawn(const ModuleSpec& spec, const std::map<std::string, std::string>& extra_env) override {
    if (fail_spawn) throw std::system_error(EAGAIN, std::generic_category(), "fork");
    const pid_t pid = next_pid_++;
    Child c;
    c.name = spec.name;
    c.env = spec.env;
    c.started = clock_.now();
    for (const auto& [k, v] : extra_env) c.env[k] = v;
    children[pid] = c;
    spawned.push_back(pid);
    return pid;
  }

  void signal_group(pid_t pid, int signo) override {
    Child& c = children.at(pid);
    c.signals.emplace_back(clock_.now(), signo);
    if (!c.alive) return;
    switch (signo) {
      case SIGKILL: end(pid, SIGKILL); break;
      case SIGSTOP: c.stopped = true; break;
      case SIGCONT:
        c.stopped = false;
        if (c.term_pending) end(pid, SIGTERM);
        break;
      case SIGTERM:
        if (c.ignores_term) break;
        if (c.stopped)
          c.term_pending = true;
        else
          end(pid, SIGTERM);
        break;
    }
  }

  std::optional<ChildExit> reap() override {
    if (exits_.empty()) return std::nullopt;
    const ChildExit e = exits_.front();
    exits_.pop_front();
    return e;
  }

  // Nothing runs while the supervisor waits: time passes, nothing more ends.
  void wait_for_exit(module::Duration timeout) override {
    if (exits_.empty()) clock_.advance(timeout);
  }

  // The child ends by itself with `code`.
  void exit(pid_t pid, int code) { end(pid, (code & 0xff) << 8); }
  // The first time `signo` reached pid, or nullopt.
  std::optional<TimePoint> signalled(pid_t pid, int signo) const {
    for (const auto& [t, s] : children.at(pid).signals)
      if (s == signo) return t;
    return std::nullopt;
  }
  std::vector<pid_t> alive() const {
    std::vector<pid_t> v;
    for (const auto& [pid, c] : children)
      if (c.alive) v.push_back(pid);
    return v;
  }

  std::map<pid_t, Child> children;
  std::vector<pid_t> spawned;
  bool fail_spawn = false;

 private:
  void end(pid_t pid, int status) {
    children.at(pid).alive = false;
    exits_.push_back({pid, status});
    ::kill(::getpid(), SIGCHLD);
  }

  ManualTimers& clock_;
  pid_t next_pid_ = 4000;
  std::deque<ChildExit> exits_;
};

class SupervisorTest : public testing::Test {
 protected:
  SupervisorTest() : procs(clock) {
    cfg.self.name = "watchdog";
    cfg.self.lcm_url = "memq://";
    cfg.self.errors.print_severity = module::kSeverityNone;
    cfg.self.extra_signals.push_back(SIGCHLD);
    cfg.dead_after = 2000ms;
    cfg.check_period = 200ms;
    cfg.term_grace = 1000ms;
    cfg.startup_grace = 5000ms;
    cfg.backoff = {500ms, 4000ms, 2.0, 2000ms};
  }

  void add(const std::string& name, bool start = true) {
    ModuleSpec s;
    s.name = name;
    s.path = "/usr/libexec/advee/" + name;
    s.start = start;
    cfg.modules.push_back(s);
  }

  // The supervisor's Module and the supervisor, started.
  void start() {
    self = std::make_unique<module::Module>(cfg.self, clock);
    phase_sub = std::make_unique<module::Subscription<Phase_t>>(
        self->lcm(), "CM_DATA_MODULES", [this](const Phase_t& m) { phases.push_back({clock.now(), m}); });
    sup = std::make_unique<Supervisor>(*self, cfg, procs);
    if (notifier) sup->notify_systemd(*notifier);
    sup->start();
    settle();
  }

  // Passes of the loop that do not wait, until everything ready is handled
  // (memq delivers on the next pass, one message per pass; a command acts
  // on the pass after): two passes in a row after which no message, timer
  // or SIGCHLD is waiting. Once the supervisor's Module has ended, its loop
  // no longer runs: what it published last is delivered directly.
  void settle() {
    for (int quiet = 0, i = 0; quiet < 2 && i < 64 && self->run_once(0ms); ++i)
      quiet = nothing_ready() ? quiet + 1 : 0;
    while (self->lcm().handleTimeout(0) > 0) {
    }
  }
  bool nothing_ready() {
    pollfd p[2] = {{self->lcm().getFileno(), POLLIN, 0}, {clock.fd(), POLLIN, 0}};
    sigset_t pending;
    sigpending(&pending);
    return ::poll(p, 2, 0) == 0 && !sigismember(&pending, SIGCHLD);
  }
  // `d` of supervisor time in steps (10 ms: 1/20 of a check period); each
  // step first calls each_step (the modules' side: announcing, crashing).
  void run_for(module::Duration d, module::Duration step = 10ms) {
    const TimePoint end = clock.now() + d;
    while (clock.now() < end) {
      clock.advance(step);
      if (each_step) each_step();
      settle();
    }
  }
  // Runs until pred() (checked every 10 ms step) or `limit`; returns pred().
  bool run_until(const std::function<bool()>& pred, module::Duration limit = 60s) {
    const TimePoint end = clock.now() + limit;
    while (!pred() && clock.now() < end) run_for(10ms);
    return pred();
  }

  void announce(const std::string& name, pid_t pid, std::int8_t state = common::data_state_t::RUN) {
    common::data_state_t m;
    m.utime = 1;
    m.module = name;
    m.state = state;
    m.pid = pid;
    self->lcm().publish("CM_DATA_STATE", &m);
    settle();
  }
  void command(const std::string& target, std::int8_t state) {
    common::cmd_state_t c;
    c.utime = 1;
    c.module = "supervisor_test";
    c.target = target;
    c.state = state;
    c.manual = true;
    self->lcm().publish("CM_CMD_STATE", &c);
    settle();
  }
  // Every module with a live child announces each second (like a module's
  // announce_period).
  void keep_announcing() {
    each_step = [this, next = clock.now() + 1s]() mutable {
      if (clock.now() < next) return;
      next += 1s;
      for (pid_t pid : procs.alive()) announce(procs.children.at(pid).name, pid);
    };
  }
  // The newest published phase of target, or nullptr.
  const Phase_t* last_phase(const std::string& target) const {
    for (auto it = phases.rbegin(); it != phases.rend(); ++it)
      if (it->second.target == target) return &it->second;
    return nullptr;
  }
  pid_t newest(const std::string& name) const {
    for (auto it = procs.spawned.rbegin(); it != procs.spawned.rend(); ++it)
      if (procs.children.at(*it).name == name) return *it;
    return 0;
  }
  std::size_t starts(const std::string& name) const {
    return std::count_if(procs.spawned.begin(), procs.spawned.end(),
                         [&](pid_t p) { return procs.children.at(p).name == name; });
  }

  // In the order of their lifetimes: the supervisor goes first.
  ManualTimers clock;
  FakeProcesses procs;
  SupervisorConfig cfg;
  std::vector<std::pair<TimePoint, Phase_t>> phases;
  std::function<void()> each_step;
  std::unique_ptr<SystemdNotifier> notifier;
  std::unique_ptr<module::Module> self;
  std::unique_ptr<module::Subscription<Phase_t>> phase_sub;
  std::unique_ptr<Supervisor> sup;
};

TEST_F(SupervisorTest, StartsTheModulesAndFollowsTheirAnnouncements) {
  add("tmod");
  add("other");
  start();
  ASSERT_EQ(procs.spawned.size(), 2u);
  const pid_t p = newest("tmod");
  ASSERT_NE(last_phase("tmod"), nullptr);
  EXPECT_EQ(last_phase("tmod")->phase, Phase_t::STARTING);
  EXPECT_EQ(last_phase("tmod")->pid, p);
  EXPECT_EQ(sup->summary(), "0/2 modules running");
  // The modules talk on the supervisor's bus.
  EXPECT_EQ(procs.children.at(p).env.at("LCM_DEFAULT_URL"), "memq://");
  announce("tmod", p);
  EXPECT_EQ(last_phase("tmod")->phase, Phase_t::RUNNING);
  EXPECT_EQ(sup->summary(), "1/2 modules running");
}

TEST_F(SupervisorTest, AStoppedModuleIsReplacedWithinThreeSeconds) {
  add("tmod");
  start();
  const pid_t p1 = newest("tmod");
  announce("tmod", p1);
  run_for(1000ms);
  // The worst case: stopped right after an announcement.
  announce("tmod", p1);
  const TimePoint t0 = clock.now();
  procs.signal_group(p1, SIGSTOP);
  ASSERT_TRUE(run_until([&] { return starts("tmod") == 2; }));
  const auto term = procs.signalled(p1, SIGTERM);
  const auto cont = procs.signalled(p1, SIGCONT);
  ASSERT_TRUE(term && cont);
  // Dead once the announcement is older than dead_after: at the first check
  // after 2000 ms; SIGCONT with SIGTERM, or a stopped module never ends.
  EXPECT_GT(ms(*term - t0), 2000);
  EXPECT_LE(ms(*term - t0), 2000 + 200);
  EXPECT_EQ(*cont, *term);
  EXPECT_EQ(procs.children.at(p1).alive, false);
  // Reaped, restarted on the next check (no back-off for a first failure).
  const long restart = ms(procs.children.at(newest("tmod")).started - t0);
  std::printf("stopped module: SIGTERM after %ld ms, new instance started after %ld ms\n",
              ms(*term - t0), restart);
  EXPECT_LE(restart, 2000 + 2 * 200);  // leaves the new process 600 ms of the 3 s to announce
  EXPECT_FALSE(procs.signalled(p1, SIGKILL));
}

TEST_F(SupervisorTest, AnnouncementsFromAnotherPidDoNotKeepAModuleAlive) {
  add("tmod");
  start();
  const pid_t p1 = newest("tmod");
  announce("tmod", p1);
  const TimePoint t0 = clock.now();
  each_step = [&] {
    if (ms(clock.now() - t0) % 500 == 0) announce("tmod", p1 + 1000);  // a stray copy
  };
  ASSERT_TRUE(run_until([&] { return procs.signalled(p1, SIGTERM).has_value(); }, 5s));
  EXPECT_LE(ms(*procs.signalled(p1, SIGTERM) - t0), 2200);
}

TEST_F(SupervisorTest, AHungModuleIsKilledAfterTheTermGrace) {
  add("tmod");
  start();
  const pid_t p1 = newest("tmod");
  procs.children.at(p1).ignores_term = true;
  announce("tmod", p1);
  ASSERT_TRUE(run_until([&] { return procs.signalled(p1, SIGKILL).has_value(); }));
  const TimePoint term = *procs.signalled(p1, SIGTERM);
  const TimePoint kill = *procs.signalled(p1, SIGKILL);
  EXPECT_GE(ms(kill - term), 1000);  // term_grace
  EXPECT_LE(ms(kill - term), 1000 + 200);
  run_for(10ms);
  ASSERT_NE(last_phase("tmod"), nullptr);
  EXPECT_EQ(last_phase("tmod")->exit_status, 128 + SIGKILL);
  ASSERT_TRUE(run_until([&] { return starts("tmod") == 2; }, 1s));
}

TEST_F(SupervisorTest, AModuleThatNeverAnnouncesIsTerminatedAfterTheStartupGrace) {
  add("tmod");
  start();
  const pid_t p1 = newest("tmod");
  const TimePoint t0 = procs.children.at(p1).started;
  ASSERT_TRUE(run_until([&] { return procs.signalled(p1, SIGTERM).has_value(); }));
  EXPECT_GT(ms(*procs.signalled(p1, SIGTERM) - t0), 5000);
  EXPECT_LE(ms(*procs.signalled(p1, SIGTERM) - t0), 5000 + 200);
}

TEST_F(SupervisorTest, AKilledModuleIsRestartedAndItsSignalReported) {
  add("tmod");
  start();
  keep_announcing();
  const pid_t p1 = newest("tmod");
  run_for(3000ms);  // longer than stable (2 s): the next restart is immediate
  const TimePoint t0 = clock.now();
  procs.signal_group(p1, SIGKILL);  // from outside, not by the supervisor
  ASSERT_TRUE(run_until([&] { return starts("tmod") == 2; }, 5s));
  EXPECT_LE(ms(procs.children.at(newest("tmod")).started - t0), 200);
  bool reported = false;
  for (const auto& [t, ph] : phases)
    reported |= ph.target == "tmod" && ph.phase == Phase_t::TERMINATED &&
                ph.exit_status == 128 + SIGKILL && ph.next_start_ms == 0;
  EXPECT_TRUE(reported);
}

TEST_F(SupervisorTest, ACrashLoopBacksOff) {
  add("crash");
  start();
  std::vector<TimePoint> exits;
  // Each instance exits with 0x41 200 ms after its start.
  each_step = [&] {
    for (pid_t pid : procs.alive())
      if (clock.now() - procs.children.at(pid).started >= 200ms) {
        procs.exit(pid, 0x41);
        exits.push_back(clock.now());
      }
  };
  run_for(16s);
  std::vector<int> delays;
  for (const auto& [t, ph] : phases)
    if (ph.target == "crash" && ph.phase == Phase_t::TERMINATED) {
      EXPECT_EQ(ph.exit_status, 0x41);
      delays.push_back(ph.next_start_ms);
    }
  // 0 for the first failure, then 0.5 s doubling, capped at 4 s.
  ASSERT_GE(delays.size(), 6u);
  EXPECT_EQ(std::vector<int>(delays.begin(), delays.begin() + 6),
            (std::vector<int>{0, 500, 1000, 2000, 4000, 4000}));
  // Each start waits the announced delay, then at most one check period.
  std::vector<TimePoint> started;
  for (pid_t p : procs.spawned) started.push_back(procs.children.at(p).started);
  ASSERT_GE(started.size(), 6u);
  for (std::size_t i = 0; i + 1 < started.size() && i < delays.size(); ++i) {
    const long waited = ms(started[i + 1] - exits[i]);
    EXPECT_GE(waited, delays[i]) << "start " << i + 1;
    EXPECT_LE(waited, delays[i] + 200) << "start " << i + 1;
  }
}

TEST_F(SupervisorTest, AFailedStartIsRetriedWithBackOff) {
  add("tmod");
  procs.fail_spawn = true;
  start();
  ASSERT_NE(last_phase("tmod"), nullptr);
  EXPECT_EQ(last_phase("tmod")->phase, Phase_t::TERMINATED);
  EXPECT_EQ(last_phase("tmod")->pid, 0);
  procs.fail_spawn = false;
  run_for(200ms);  // the first retry is immediate: on the next check
  EXPECT_EQ(starts("tmod"), 1u);
}

TEST_F(SupervisorTest, CommandsPauseRunTerminateRun) {
  add("tmod");
  add("other");
  start();
  keep_announcing();
  run_for(1000ms);
  const pid_t p1 = newest("tmod");
  const pid_t other = newest("other");

  // PAUSE is the module's own business: recorded, nothing signalled.
  command("tmod", common::data_state_t::PAUSE);
  EXPECT_EQ(last_phase("tmod")->command, common::data_state_t::PAUSE);
  run_for(5000ms, 100ms);  // a paused module keeps announcing: it stays
  EXPECT_TRUE(procs.children.at(p1).signals.empty());
  command("tmod", common::data_state_t::RUN);
  EXPECT_EQ(last_phase("tmod")->command, common::data_state_t::RUN);
  EXPECT_EQ(starts("tmod"), 1u);

  // TERMINATE: SIGTERM at once, then DOWN and kept down.
  const TimePoint t0 = clock.now();
  command("tmod", common::data_state_t::TERMINATE);
  ASSERT_TRUE(procs.signalled(p1, SIGTERM));
  EXPECT_EQ(*procs.signalled(p1, SIGTERM), t0);
  EXPECT_EQ(last_phase("tmod")->phase, Phase_t::DOWN);
  run_for(20s, 100ms);  // 5 times the longest back-off
  EXPECT_EQ(starts("tmod"), 1u);
  EXPECT_TRUE(procs.children.at(other).alive);  // the other one is not affected
  EXPECT_TRUE(procs.children.at(other).signals.empty());

  // RUN brings it back at once, without waiting for a check or a back-off.
  command("tmod", common::data_state_t::RUN);
  EXPECT_EQ(starts("tmod"), 2u);
  EXPECT_EQ(last_phase("tmod")->phase, Phase_t::STARTING);
}

TEST_F(SupervisorTest, StartFalseWaitsForRun) {
  add("tmod", false);
  start();
  ASSERT_NE(last_phase("tmod"), nullptr);
  EXPECT_EQ(last_phase("tmod")->phase, Phase_t::DOWN);
  run_for(20s, 100ms);
  EXPECT_EQ(starts("tmod"), 0u);
  command("tmod", common::data_state_t::RUN);
  EXPECT_EQ(starts("tmod"), 1u);
}

TEST_F(SupervisorTest, TerminateEndsEveryModuleKillingThoseThatStay) {
  add("polite");
  add("hung");
  start();
  keep_announcing();
  run_for(1000ms);
  const pid_t polite = newest("polite"), hung = newest("hung");
  procs.children.at(hung).ignores_term = true;
  const TimePoint t0 = clock.now();
  command("*", common::data_state_t::TERMINATE);  // the supervisor's own TERMINATE too
  EXPECT_EQ(self->state(), module::State::Terminate);
  EXPECT_FALSE(self->run_once(0ms));
  EXPECT_TRUE(procs.alive().empty());
  EXPECT_EQ(*procs.signalled(polite, SIGTERM), t0);
  ASSERT_TRUE(procs.signalled(hung, SIGKILL));
  EXPECT_GE(ms(*procs.signalled(hung, SIGKILL) - t0), 1000);  // term_grace
  EXPECT_LE(ms(*procs.signalled(hung, SIGKILL) - t0), 1000 + 100);
  EXPECT_EQ(last_phase("polite")->phase, Phase_t::DOWN);
  EXPECT_EQ(last_phase("hung")->phase, Phase_t::DOWN);
  EXPECT_EQ(last_phase("hung")->exit_status, 128 + SIGKILL);
}

// systemd's side: a datagram socket named in NOTIFY_SOCKET.
class SupervisorNotifyTest : public SupervisorTest {
 protected:
  void SetUp() override {
    dir_ = std::filesystem::temp_directory_path() / ("advee-sup-notify-" + std::to_string(::getpid()));
    std::filesystem::create_directories(dir_);
    const auto path = dir_ / "notify.sock";
    fd_ = ::socket(AF_UNIX, SOCK_DGRAM | SOCK_CLOEXEC, 0);
    ASSERT_GE(fd_, 0);
    sockaddr_un sa{};
    sa.sun_family = AF_UNIX;
    std::snprintf(sa.sun_path, sizeof sa.sun_path, "%s", path.c_str());
    ASSERT_EQ(::bind(fd_, reinterpret_cast<sockaddr*>(&sa), sizeof sa), 0);
    ::setenv("NOTIFY_SOCKET", path.c_str(), 1);
    ::setenv("WATCHDOG_USEC", "400000", 1);  // pings every 200 ms
  }
  void TearDown() override {
    ::unsetenv("NOTIFY_SOCKET");
    ::unsetenv("WATCHDOG_USEC");
    if (fd_ >= 0) ::close(fd_);
    std::filesystem::remove_all(dir_);
  }
  // Every datagram sent so far, with the time it was read (sd_notify sends
  // synchronously: read right after each step, a message's time is exact).
  void drain() {
    char buf[512];
    ssize_t n;
    while ((n = ::recv(fd_, buf, sizeof buf, MSG_DONTWAIT)) > 0)
      got.emplace_back(clock.now(), std::string(buf, static_cast<std::size_t>(n)));
  }
  std::filesystem::path dir_;
  int fd_ = -1;
  std::vector<std::pair<TimePoint, std::string>> got;
};

TEST_F(SupervisorNotifyTest, ReadyThenStatusAndAPingEveryHalfWatchdogUsec) {
  notifier = std::make_unique<SystemdNotifier>();
  ASSERT_TRUE(notifier->active());
  ASSERT_EQ(notifier->ping_interval(), std::chrono::microseconds(200000));
  add("tmod");
  start();
  drain();
  ASSERT_FALSE(got.empty());
  EXPECT_EQ(got.back().second, "READY=1\nSTATUS=0/1 modules running");  // after the start
  const TimePoint t0 = clock.now();
  announce("tmod", newest("tmod"));
  for (int i = 0; i < 200; ++i) {
    run_for(10ms);
    drain();
  }
  std::vector<long> pings;
  bool running = false;
  for (const auto& [t, m] : got) {
    if (m == "WATCHDOG=1") pings.push_back(ms(t - t0));
    running |= m == "STATUS=1/1 modules running";
  }
  EXPECT_TRUE(running);
  // 2 s from the start: a ping at every 200 ms, from the loop.
  EXPECT_EQ(pings, (std::vector<long>{200, 400, 600, 800, 1000, 1200, 1400, 1600, 1800, 2000}));
  const std::size_t before = got.size();
  command("*", common::data_state_t::TERMINATE);
  drain();
  ASSERT_GT(got.size(), before);
  EXPECT_EQ(got[before].second, "STOPPING=1");  // first, then the modules end
  EXPECT_EQ(got.back().second, "STATUS=0/1 modules running");
}

}  // namespace
