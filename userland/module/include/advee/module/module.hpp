// SPDX-License-Identifier: GPL-2.0
// One robot module (thesis 3.3): its state machine, its LCM instance, its
// error reporter and one poll loop that handles LCM messages, signals, the
// 1 Hz CM_DATA_STATE announcement and the module's periodic work.
//
//   Module m(opts);                       // INIT: signals blocked, LCM up
//   m.every(250ms, [&] { poll_devices(); });  // runs only in RUN
//   return m.run();                       // RUN/PAUSE/... until TERMINATE
//
// CM_CMD_STATE messages addressed to the module (target == name or "*")
// move the state machine when the transition table allows it; SIGTERM,
// SIGINT and SIGHUP mean TERMINATE. Everything runs on the thread that calls
// run(); other threads talk to it through post(). Time comes from a
// TimerSource: the real monotonic one by default, a ManualTimers in tests.
#pragma once

#include <chrono>
#include <filesystem>
#include <functional>
#include <memory>
#include <mutex>
#include <string>
#include <vector>

#include "advee/module/config.hpp"
#include "advee/module/error.hpp"
#include "advee/module/exit_code.hpp"
#include "advee/module/periodic.hpp"
#include "advee/signal_fd.hpp"
#include "advee/module/state.hpp"
#include "advee/module/timers.hpp"

namespace lcm {
class LCM;
class ReceiveBuffer;
}  // namespace lcm
namespace common {
class cmd_state_t;
}

namespace advee::module {

class Module {
 public:
  // Throws ModuleExit (resource) when LCM or the log directory cannot be set up.
  explicit Module(ModuleOptions opts);
  // With the caller's time source (which must outlive the module).
  Module(ModuleOptions opts, TimerSource& timers);
  ~Module();
  Module(const Module&) = delete;
  Module& operator=(const Module&) = delete;

  const std::string& name() const { return opts_.name; }
  const ModuleOptions& options() const { return opts_; }
  lcm::LCM& lcm() { return *lcm_; }
  // The URL the module's LCM uses (advee/msgs/bus.hpp: module.lcm_url, else
  // LCM_DEFAULT_URL, else /etc/advee/lcm.conf, else LCM's default).
  const std::string& lcm_url() const { return lcm_url_; }
  ErrorReporter& errors() { return *errors_; }
  // The loop's time: read now() here, not from a clock of your own.
  TimerSource& timers() { return timers_; }
  State state() const { return state_; }
  // Empty when the module has no log directory.
  const std::filesystem::path& log_dir() const { return log_dir_; }

  // Called on every state change, after the state changed and before the
  // announcement. Throwing ModuleExit ends run() with its code.
  void on_state_change(std::function<void(State from, State to)> fn);
  // fn every `period` (the first time one period from now); with only_in_run
  // it is skipped outside RUN, which is how PAUSE stops a driver's polling.
  void every(std::chrono::nanoseconds period, std::function<void()> fn, bool only_in_run = true);
  // fn when fd becomes readable (level-triggered: fn must consume it).
  void watch_fd(int fd, std::function<void()> fn);
  // fn for one of opts.extra_signals.
  void on_signal(int signo, std::function<void(const signalfd_siginfo&)> fn);
  // Thread-safe: fn runs on the loop thread.
  void post(std::function<void()> fn);

  // Moves the state machine; false (and a notice) when the table refuses it.
  bool request_state(State to, bool manual, std::string_view why);
  // Acts on a CM_CMD_STATE addressed to this module (called on the loop).
  void obey(const common::cmd_state_t& m);
  // Publishes CM_DATA_STATE now (also done every announce_period).
  void announce();

  // Leaves INIT for the configured start state and loops until TERMINATE.
  // Returns the exit code: 0, or a ModuleExit's code thrown by a handler.
  int run();
  // One poll + dispatch, for tests and for callers with their own loop; false
  // once the module is in TERMINATE.
  bool run_once(std::chrono::milliseconds max_wait);

 private:
  Module(ModuleOptions opts, std::unique_ptr<TimerSource> own, TimerSource* external);
  void handle_signal(const signalfd_siginfo& si);

  ModuleOptions opts_;
  advee::SignalFd signals_;  // first: the mask must be in place before LCM starts threads
  std::unique_ptr<TimerSource> own_timers_;  // before every Timer: they cancel into it
  TimerSource& timers_;
  std::string lcm_url_;
  std::unique_ptr<lcm::LCM> lcm_;
  std::filesystem::path log_dir_;
  std::unique_ptr<ErrorReporter> errors_;
  State state_ = State::Init;
  Timer announce_timer_;
  Waker waker_;
  std::vector<Timer> periodics_;
  std::vector<std::pair<int, std::function<void()>>> fds_;
  std::vector<std::pair<int, std::function<void(const signalfd_siginfo&)>>> signal_handlers_;
  std::vector<std::function<void(State, State)>> state_hooks_;
  std::mutex post_mutex_;
  std::vector<std::function<void()>> posted_;
};

// Runs body() and turns what escapes it into the exit-code convention:
// ModuleExit -> its code, ConfigError -> other+1, std::system_error ->
// resource+1, any other exception -> other+2. The message goes to stderr.
int guarded_main(std::string_view module_name, const std::function<int()>& body);

}  // namespace advee::module
