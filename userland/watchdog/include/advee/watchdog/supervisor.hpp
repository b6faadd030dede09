// SPDX-License-Identifier: GPL-2.0
// The watchdog supervisor (thesis 3.6, algorithm 3.1), one poll loop instead
// of a thread per module: it starts the configured modules, follows their
// CM_DATA_STATE announcements, terminates a module whose newest announcement
// is older than dead_after (SIGTERM + SIGCONT, SIGKILL after term_grace),
// restarts it with back-off, and obeys CM_CMD_STATE addressed to a module
// (TERMINATE keeps it down, RUN starts it again). Every phase change is
// published on CM_DATA_MODULES and reported as a notice or warning. Time is
// the Module's (its TimerSource) and processes are started, signalled and
// reaped through Processes, so the unit tests run all of it on a manual
// clock with fake processes.
#pragma once

#include <sys/types.h>

#include <chrono>
#include <functional>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "advee/module/module.hpp"
#include "advee/module/subscription.hpp"
#include "advee/watchdog/backoff.hpp"
#include "advee/watchdog/config.hpp"
#include "advee/watchdog/process.hpp"
#include "advee/watchdog/systemd_notify.hpp"

namespace common {
class data_state_t;
class cmd_state_t;
}  // namespace common

namespace advee::watchdog {

enum class Phase : std::int8_t { Down = 0, Starting = 1, Running = 2, Terminating = 3, Terminated = 4 };
std::string_view to_string(Phase p);

class Supervisor {
 public:
  // `self` is the supervisor's own Module (created with SIGCHLD among its
  // extra signals); the supervisor registers its handlers on it. Both
  // `self` and `processes` must outlive the supervisor.
  Supervisor(module::Module& self, SupervisorConfig cfg, Processes& processes);
  ~Supervisor();  // shutdown()
  Supervisor(const Supervisor&) = delete;
  Supervisor& operator=(const Supervisor&) = delete;

  // Reports to systemd through n (which must outlive the supervisor):
  // STATUS= on every phase change, WATCHDOG=1 every ping interval from the
  // loop (a hung loop stops pinging), READY=1 at the end of start(),
  // STOPPING=1 when shutdown() begins. Call before start().
  void notify_systemd(SystemdNotifier& n);
  // Starts the modules marked start: true.
  void start();
  // Terminates every running module (SIGTERM, SIGKILL after term_grace) and
  // reaps them. Idempotent.
  void shutdown();
  // "2/3 modules running"
  std::string summary() const;

 private:
  struct Proc {
    ModuleSpec spec;
    Backoff backoff;
    Phase phase = Phase::Down;
    module::State command = module::State::Run;  // what CM_CMD_STATE last asked for
    pid_t pid = 0;
    module::TimePoint started{}, last_announce{}, kill_at{}, next_start{};
    bool killed = false;  // SIGKILL sent
    int restarts = 0;
    int exit_status = -1;
    bool started_once = false;
  };

  void check();
  void launch(Proc& p);
  void terminate(Proc& p, const std::string& why);
  void reap();
  void set_phase(Proc& p, Phase ph);
  void publish(const Proc& p);
  void on_announce(const common::data_state_t& m);
  void on_command(const common::cmd_state_t& m);
  Proc* find(const std::string& name);
  Proc* find(pid_t pid);
  module::TimePoint now() { return self_.timers().now(); }

  module::Module& self_;
  SupervisorConfig cfg_;
  Processes& processes_;
  SystemdNotifier* notifier_ = nullptr;
  std::vector<Proc> procs_;
  std::unique_ptr<module::Subscription<common::data_state_t>> state_sub_;
  std::unique_ptr<module::Subscription<common::cmd_state_t>> cmd_sub_;
  bool shut_down_ = false;
};

}  // namespace advee::watchdog
