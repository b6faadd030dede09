// SPDX-License-Identifier: GPL-2.0
#include "advee/watchdog/process.hpp"

#include <signal.h>
#include <sys/wait.h>
#include <time.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>
#include <system_error>
#include <vector>

extern char** environ;

namespace advee::watchdog {

pid_t SystemProcesses::spawn(const ModuleSpec& spec, const std::map<std::string, std::string>& extra_env) {
  // Everything the child needs is built before fork: after it, in a process
  // with other threads (LCM's), only async-signal-safe calls are allowed.
  std::map<std::string, std::string> env;
  for (char** e = environ; *e; ++e) {
    const char* eq = std::strchr(*e, '=');
    if (eq) env[std::string(*e, static_cast<std::size_t>(eq - *e))] = eq + 1;
  }
  // The supervisor's own systemd channel is not the module's.
  env.erase("NOTIFY_SOCKET");
  env.erase("WATCHDOG_USEC");
  env.erase("WATCHDOG_PID");
  for (const auto& [k, v] : spec.env) env[k] = v;
  for (const auto& [k, v] : extra_env) env[k] = v;
  std::vector<std::string> env_strings;
  for (const auto& [k, v] : env) env_strings.push_back(k + "=" + v);
  std::vector<char*> envp;
  for (auto& s : env_strings) envp.push_back(s.data());
  envp.push_back(nullptr);
  std::vector<std::string> args{spec.path};
  args.insert(args.end(), spec.args.begin(), spec.args.end());
  std::vector<char*> argv;
  for (auto& a : args) argv.push_back(a.data());
  argv.push_back(nullptr);
  sigset_t empty;
  sigemptyset(&empty);

  const pid_t pid = ::fork();
  if (pid < 0) throw std::system_error(errno, std::generic_category(), "fork");
  if (pid == 0) {
    ::setpgid(0, 0);
    ::sigprocmask(SIG_SETMASK, &empty, nullptr);
    ::close_range(3, ~0U, 0);
    ::execve(argv[0], argv.data(), envp.data());
    ::_exit(127);
  }
  // Also from the parent, so that signal_group() works even before the
  // child ran (whichever setpgid comes first wins, both set the same).
  ::setpgid(pid, pid);
  return pid;
}

void SystemProcesses::signal_group(pid_t pid, int signo) {
  if (pid <= 0) return;
  if (::kill(-pid, signo) < 0) ::kill(pid, signo);
}

std::optional<ChildExit> SystemProcesses::reap() {
  int status = 0;
  const pid_t pid = ::waitpid(-1, &status, WNOHANG);
  if (pid <= 0) return std::nullopt;
  return ChildExit{pid, status};
}

void SystemProcesses::wait_for_exit(module::Duration timeout) {
  // SIGCHLD is blocked: take it from the pending set (reap() then finds the
  // child). A SIGCHLD that was not blocked would just let this time out.
  sigset_t chld;
  sigemptyset(&chld);
  sigaddset(&chld, SIGCHLD);
  const auto ns = std::chrono::duration_cast<std::chrono::nanoseconds>(timeout).count();
  timespec ts{};
  if (ns > 0) {
    ts.tv_sec = ns / 1'000'000'000;
    ts.tv_nsec = ns % 1'000'000'000;
  }
  ::sigtimedwait(&chld, nullptr, &ts);
}

}  // namespace advee::watchdog
