// SPDX-License-Identifier: GPL-2.0
// The Module loop on LCM's in-process provider (memq://): announcements,
// CM_CMD_STATE addressed to the module, PAUSE stopping the periodic work,
// manual-only STOP, TERMINATE by command and by SIGTERM, ModuleExit codes.
#include <gtest/gtest.h>
#include <pthread.h>
#include <signal.h>
#include <sys/prctl.h>
#include <unistd.h>

#include <chrono>
#include <lcm/lcm-cpp.hpp>
#include <thread>
#include <vector>

#include "advee/module/manual_loop.hpp"
#include "advee/module/module.hpp"
#include "advee/module/subscription.hpp"
#include "common/cmd_state_t.hpp"
#include "common/data_state_t.hpp"

using namespace advee::module;
using namespace std::chrono_literals;

namespace {

struct Announcements {
  std::vector<common::data_state_t> msgs;
  State last() const { return msgs.empty() ? State::Unknown : static_cast<State>(msgs.back().state); }
};

// Every Module runs on a manual clock: time moves only in advance(), so the
// tests assert exact counts and take no wall-clock time.
class ModuleTest : public testing::Test {
 protected:
  ModuleOptions opts(std::chrono::milliseconds announce = 1000ms) {
    ModuleOptions o;
    o.name = "driver_test";
    o.lcm_url = "memq://";
    o.errors.print_severity = kSeverityNone;
    o.announce_period = announce;
    return o;
  }
  void command(Module& m, const std::string& target, State s, bool manual = false) {
    common::cmd_state_t c;
    c.utime = 1;
    c.module = "test";
    c.target = target;
    c.state = static_cast<std::int8_t>(s);
    c.manual = manual;
    m.lcm().publish("CM_CMD_STATE", &c);
    settle(m);
  }
  // memq delivers on the next handle, a command acts on the next loop pass
  // and an announcement reaches a subscriber on the pass after: a few passes
  // that do not wait handle everything that is ready.
  static void settle(Module& m) {
    for (int i = 0; i < 4; ++i) m.run_once(0ms);
  }
  // `d` of module time in steps of `step`, the loop settling after each.
  void spin(Module& m, std::chrono::milliseconds d) { run_manual(m, clock, d); }
  ManualTimers clock;
};

TEST_F(ModuleTest, TurnsTransparentHugePagesOff) {
  // A 2 MB huge page in a thread stack would cost a module more than all
  // its own memory (docs/daemons.md "Resource use").
  Module m(opts(), clock);
  EXPECT_EQ(prctl(PR_GET_THP_DISABLE, 0, 0, 0, 0), 1);
}

TEST_F(ModuleTest, StartsInInitAndAnnouncesTheStartState) {
  Module m(opts(), clock);
  Announcements a;
  Subscription<common::data_state_t> sub(m.lcm(), "CM_DATA_STATE", [&](const common::data_state_t& s) { a.msgs.push_back(s); });
  EXPECT_EQ(m.state(), State::Init);
  ASSERT_TRUE(m.request_state(State::Run, false, "test"));
  m.run_once(0ms);
  ASSERT_EQ(a.msgs.size(), 1u);
  EXPECT_EQ(a.msgs[0].module, "driver_test");
  EXPECT_EQ(a.last(), State::Run);
  EXPECT_EQ(a.msgs[0].pid, ::getpid());
}

TEST_F(ModuleTest, AnnouncesEveryPeriod) {
  Module m(opts(20ms), clock);
  Announcements a;
  Subscription<common::data_state_t> sub(m.lcm(), "CM_DATA_STATE", [&](const common::data_state_t& s) { a.msgs.push_back(s); });
  m.request_state(State::Pause, false, "test");
  spin(m, 19ms);
  EXPECT_EQ(a.msgs.size(), 1u);  // the change; the first period is not over
  spin(m, 181ms);
  // 1 for the change + one at each of 20, 40, ..., 200 ms.
  EXPECT_EQ(a.msgs.size(), 11u);
  for (const auto& s : a.msgs) EXPECT_EQ(s.state, common::data_state_t::PAUSE);
}

TEST_F(ModuleTest, ALateLoopAnnouncesOnceNotInABurst) {
  Module m(opts(20ms), clock);
  Announcements a;
  Subscription<common::data_state_t> sub(m.lcm(), "CM_DATA_STATE", [&](const common::data_state_t& s) { a.msgs.push_back(s); });
  clock.advance(100ms);  // five periods pass without the loop running
  settle(m);
  EXPECT_EQ(a.msgs.size(), 1u);
  spin(m, 19ms);  // the phase is kept: next at 120 ms
  EXPECT_EQ(a.msgs.size(), 1u);
  spin(m, 1ms);
  EXPECT_EQ(a.msgs.size(), 2u);
}

TEST_F(ModuleTest, PauseStopsThePeriodicWorkAndRunResumesIt) {
  Module m(opts(), clock);
  int polls = 0;
  m.every(5ms, [&] { ++polls; });
  m.request_state(State::Run, false, "test");
  spin(m, 60ms);
  EXPECT_EQ(polls, 12);
  command(m, "driver_test", State::Pause);
  EXPECT_EQ(m.state(), State::Pause);
  spin(m, 60ms);
  EXPECT_EQ(polls, 12);
  command(m, "driver_test", State::Run);
  EXPECT_EQ(m.state(), State::Run);
  spin(m, 60ms);
  EXPECT_EQ(polls, 24);
}

TEST_F(ModuleTest, WorkOutsideRunWhenAsked) {
  Module m(opts(), clock);
  int polls = 0;
  m.every(10ms, [&] { ++polls; }, false);
  m.request_state(State::Pause, false, "test");
  spin(m, 50ms);
  EXPECT_EQ(polls, 5);
}

TEST_F(ModuleTest, CommandsForOtherModulesAreIgnoredAndStarAddressesAll) {
  Module m(opts(), clock);
  m.request_state(State::Run, false, "test");
  command(m, "driver_other", State::Pause);
  EXPECT_EQ(m.state(), State::Run);
  command(m, "*", State::Pause);
  EXPECT_EQ(m.state(), State::Pause);
}

TEST_F(ModuleTest, StopOnlyByHand) {
  Module m(opts(), clock);
  Announcements a;
  Subscription<common::data_state_t> sub(m.lcm(), "CM_DATA_STATE", [&](const common::data_state_t& s) { a.msgs.push_back(s); });
  std::vector<std::pair<State, State>> changes;
  m.on_state_change([&](State f, State t) { changes.emplace_back(f, t); });
  m.request_state(State::Run, false, "test");
  command(m, "driver_test", State::Stop, false);
  EXPECT_EQ(m.state(), State::Run);
  command(m, "driver_test", State::Stop, true);
  EXPECT_EQ(m.state(), State::Stop);
  command(m, "driver_test", State::Run, false);  // a planner cannot restart it
  EXPECT_EQ(m.state(), State::Stop);
  command(m, "driver_test", State::Run, true);
  EXPECT_EQ(m.state(), State::Run);
  const std::vector<std::pair<State, State>> want{
      {State::Init, State::Run}, {State::Run, State::Stop}, {State::Stop, State::Run}};
  EXPECT_EQ(changes, want);
  EXPECT_EQ(a.last(), State::Run);
}

TEST_F(ModuleTest, InvalidStateValuesAreIgnored) {
  Module m(opts(), clock);
  m.request_state(State::Run, false, "test");
  common::cmd_state_t c;
  c.module = "test";
  c.target = "driver_test";
  c.state = 42;
  c.manual = true;
  m.lcm().publish("CM_CMD_STATE", &c);
  for (int i = 0; i < 4; ++i) m.run_once(0ms);
  EXPECT_EQ(m.state(), State::Run);
}

TEST_F(ModuleTest, TerminateCommandEndsTheLoop) {
  Module m(opts(), clock);
  m.request_state(State::Run, false, "test");
  command(m, "driver_test", State::Terminate);
  EXPECT_EQ(m.state(), State::Terminate);
  EXPECT_FALSE(m.run_once(0ms));
  EXPECT_EQ(m.run(), 0);
}

TEST_F(ModuleTest, SigtermMeansTerminate) {
  Module m(opts(), clock);
  m.request_state(State::Run, false, "test");
  ASSERT_EQ(::kill(::getpid(), SIGTERM), 0);  // blocked: waits in the signalfd
  // Pending at once (a process-directed signal to ourselves): the first pass
  // reads it; the deadline only bounds a failure.
  m.run_once(5000ms);
  EXPECT_EQ(m.state(), State::Terminate);
}

TEST_F(ModuleTest, ASigtermDuringTheEndDoesNotOutliveTheModule) {
  sigset_t before;
  ASSERT_EQ(pthread_sigmask(SIG_SETMASK, nullptr, &before), 0);
  ASSERT_FALSE(sigismember(&before, SIGTERM));
  {
    Module m(opts(), clock);
    m.every(1ms, [] { throw ModuleExit(ExitKind::Device, 2, "gone"); });
    clock.advance(1ms);
    EXPECT_EQ(m.run(), 0x22);
    ASSERT_EQ(::kill(::getpid(), SIGTERM), 0);  // pending, the loop no longer reads it
    sigset_t pending;
    ASSERT_EQ(sigpending(&pending), 0);
    ASSERT_TRUE(sigismember(&pending, SIGTERM));
  }
  // Still alive (an unblocked pending SIGTERM would have ended the test
  // binary here): the destructor discarded it, then restored the mask.
  sigset_t pending, after;
  ASSERT_EQ(sigpending(&pending), 0);
  EXPECT_FALSE(sigismember(&pending, SIGTERM));
  ASSERT_EQ(pthread_sigmask(SIG_SETMASK, nullptr, &after), 0);
  EXPECT_FALSE(sigismember(&after, SIGTERM));
}

TEST_F(ModuleTest, ModuleExitFromWorkEndsRunWithItsCode) {
  Module m(opts(), clock);
  m.every(1ms, [] { throw ModuleExit(ExitKind::Device, 3, "sensor gone"); });
  clock.advance(1ms);
  EXPECT_EQ(m.run(), 0x23);
  EXPECT_EQ(m.state(), State::Terminate);
}

TEST_F(ModuleTest, RealTimeByDefault) {
  // Without a source of its own the module keeps time on CLOCK_MONOTONIC.
  Module m(opts());
  const auto t0 = std::chrono::steady_clock::now();
  const auto t = m.timers().now();
  EXPECT_GE(t, t0);
  EXPECT_LE(t, std::chrono::steady_clock::now());
}

TEST_F(ModuleTest, PostRunsOnTheLoopThread) {
  Module m(opts(), clock);
  bool ran = false;
  std::thread t([&] { m.post([&] { ran = true; }); });
  t.join();
  m.run_once(5000ms);  // returns as soon as the posted work is there
  EXPECT_TRUE(ran);
}

TEST(GuardedMain, ExceptionsBecomeExitCodes) {
  testing::internal::CaptureStderr();
  EXPECT_EQ(guarded_main("x", [] () -> int { throw ModuleExit(ExitKind::Resource, 4, "no memory"); }), 0x14);
  EXPECT_EQ(guarded_main("x", [] () -> int { throw ConfigError("bad"); }), 0x41);
  EXPECT_EQ(guarded_main("x", [] () -> int { throw std::runtime_error("boom"); }), 0x42);
  EXPECT_EQ(guarded_main("x", [] { return 0; }), 0);
  const auto err = testing::internal::GetCapturedStderr();
  EXPECT_NE(err.find("x: no memory (resource error 4)"), std::string::npos) << err;
}

}  // namespace
