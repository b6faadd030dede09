// SPDX-License-Identifier: GPL-2.0
// Starting, signalling and reaping the supervised processes. The supervisor
// does all of it through Processes, so its unit tests replace the real
// processes with a fake and the logic runs on a manual clock; SystemProcesses
// is the real thing. Each module runs in its own process group, so signals
// reach whatever it started too.
#pragma once

#include <sys/types.h>

#include <map>
#include <optional>
#include <string>

#include "advee/module/timers.hpp"
#include "advee/watchdog/config.hpp"

namespace advee::watchdog {

// A child that ended: its pid and waitpid(2) status.
struct ChildExit {
  pid_t pid;
  int status;
};

class Processes {
 public:
  virtual ~Processes() = default;
  // Starts spec with the supervisor's environment plus spec.env plus
  // extra_env. Throws std::system_error when it cannot.
  virtual pid_t spawn(const ModuleSpec& spec, const std::map<std::string, std::string>& extra_env) = 0;
  // Signal the process group of pid (falls back to pid alone).
  virtual void signal_group(pid_t pid, int signo) = 0;
  // One child that ended, without blocking; nullopt when none has.
  virtual std::optional<ChildExit> reap() = 0;
  // Blocks until a child may have ended (SIGCHLD) or `timeout` passed;
  // only the shutdown, which runs outside the loop, waits like this.
  virtual void wait_for_exit(module::Duration timeout) = 0;
};

// fork + execve of spec.path with spec.args. The child gets an empty signal
// mask and no inherited descriptors above stderr; an exec failure shows as
// its exit code 127. reap() is waitpid(-1, WNOHANG); wait_for_exit() waits
// for SIGCHLD, which the supervisor keeps blocked (its Module's extra_signals).
class SystemProcesses final : public Processes {
 public:
  pid_t spawn(const ModuleSpec& spec, const std::map<std::string, std::string>& extra_env) override;
  void signal_group(pid_t pid, int signo) override;
  std::optional<ChildExit> reap() override;
  void wait_for_exit(module::Duration timeout) override;
};

}  // namespace advee::watchdog
