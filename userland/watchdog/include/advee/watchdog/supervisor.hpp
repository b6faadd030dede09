// SPDX-License-Identifier: GPL-2.0
// The watchdog supervisor (thesis 3.6, algorithm 3.1), one poll loop instead
// of a thread per module: it starts the configured modules, follows their
// CM_DATA_STATE announcements, terminates a module whose newest announcement
// is older than dead_after (SIGTERM + SIGCONT, SIGKILL after term_grace),
// restarts it with back-off, and obeys CM_CMD_STATE addressed to a module
// (TERMINATE keeps it down, RUN starts it again). Every phase change is
// published on CM_DATA_MODULES and reported as a notice or warning.
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

namespace common {
class data_state_t;
class cmd_state_t;
}  // namespace common

namespace advee::watchdog {

enum class Phase : std::int8_t { Down = 0, Starting = 1, Running = 2, Terminating = 3, Terminated = 4 };
std::string_view to_string(Phase p);

class Supervisor {
 public:
  using Clock = std::chrono::steady_clock;

  // `self` is the supervisor's own Module (created with SIGCHLD among its
  // extra signals); the supervisor registers its handlers on it.
  Supervisor(module::Module& self, SupervisorConfig cfg);
  ~Supervisor();  // shutdown()
  Supervisor(const Supervisor&) = delete;
  Supervisor& operator=(const Supervisor&) = delete;

  // Starts the modules marked start: true.
  void start();
  // Terminates every running module (SIGTERM, SIGKILL after term_grace) and
  // reaps them. Idempotent.
  void shutdown();
  // Called after every phase change (for sd_notify STATUS=).
  void on_change(std::function<void()> fn) { on_change_ = std::move(fn); }
  // "2/3 modules running"
  std::string summary() const;

 private:
  struct Proc {
    ModuleSpec spec;
    Backoff backoff;
    Phase phase = Phase::Down;
    module::State command = module::State::Run;  // what CM_CMD_STATE last asked for
    pid_t pid = 0;
    Clock::time_point started{}, last_announce{}, kill_at{}, next_start{};
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

  module::Module& self_;
  SupervisorConfig cfg_;
  std::vector<Proc> procs_;
  std::function<void()> on_change_;
  std::unique_ptr<module::Subscription<common::data_state_t>> state_sub_;
  std::unique_ptr<module::Subscription<common::cmd_state_t>> cmd_sub_;
  bool shut_down_ = false;
};

}  // namespace advee::watchdog
