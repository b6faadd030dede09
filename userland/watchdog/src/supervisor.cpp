// SPDX-License-Identifier: GPL-2.0
#include "advee/watchdog/supervisor.hpp"

#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <lcm/lcm-cpp.hpp>

#include "advee/module/exit_code.hpp"
#include "advee/module/log_dir.hpp"
#include "advee/module/subscription.hpp"
#include "advee/module/time.hpp"
#include "advee/msgs/bus.hpp"
#include "advee/msgs/channels.hpp"
#include "common/cmd_state_t.hpp"
#include "common/data_module_phase_t.hpp"
#include "common/data_state_t.hpp"

namespace advee::watchdog {

using module::ErrorType;
using module::Severity;
using module::State;

std::string_view to_string(Phase p) {
  switch (p) {
    case Phase::Down: return "DOWN";
    case Phase::Starting: return "STARTING";
    case Phase::Running: return "RUNNING";
    case Phase::Terminating: return "TERMINATING";
    case Phase::Terminated: return "TERMINATED";
  }
  return "?";
}

namespace {

std::string ms_text(Millis d) { return std::to_string(d.count()) + " ms"; }

}  // namespace

Supervisor::Supervisor(module::Module& self, SupervisorConfig cfg, Processes& processes)
    : self_(self), cfg_(std::move(cfg)), processes_(processes) {
  for (const auto& spec : cfg_.modules) {
    Proc p{spec, Backoff(cfg_.backoff)};
    p.command = spec.start ? State::Run : State::Terminate;
    procs_.push_back(std::move(p));
  }
  // Announcements only update timestamps: handled inside LCM's dispatch.
  // Commands may start or signal processes: deferred to the loop proper.
  state_sub_ = std::make_unique<module::Subscription<common::data_state_t>>(
      self_.lcm(), std::string(msgs::kDataState.name),
      [this](const common::data_state_t& m) { on_announce(m); });
  cmd_sub_ = std::make_unique<module::Subscription<common::cmd_state_t>>(
      self_.lcm(), std::string(msgs::kCmdState.name),
      [this](const common::cmd_state_t& m) { self_.post([this, m] { on_command(m); }); });
  self_.on_signal(SIGCHLD, [this](const signalfd_siginfo&) { reap(); });
  self_.every(cfg_.check_period, [this] { check(); }, false);
  self_.on_state_change([this](State, State to) {
    if (to == State::Terminate) shutdown();
  });
}

Supervisor::~Supervisor() { shutdown(); }

Supervisor::Proc* Supervisor::find(const std::string& name) {
  for (auto& p : procs_)
    if (p.spec.name == name) return &p;
  return nullptr;
}

Supervisor::Proc* Supervisor::find(pid_t pid) {
  for (auto& p : procs_)
    if (p.pid == pid && pid > 0) return &p;
  return nullptr;
}

std::string Supervisor::summary() const {
  int running = 0;
  for (const auto& p : procs_) running += p.phase == Phase::Running;
  return std::to_string(running) + "/" + std::to_string(procs_.size()) + " modules running";
}

void Supervisor::notify_systemd(SystemdNotifier& n) {
  notifier_ = &n;
  if (auto iv = n.ping_interval()) self_.every(*iv, [&n] { n.ping(); }, false);
}

void Supervisor::start() {
  for (auto& p : procs_) {
    if (p.command == State::Terminate)
      publish(p);  // DOWN from the start: say so once
    else
      launch(p);
  }
  if (notifier_) notifier_->ready(summary());
}

void Supervisor::publish(const Proc& p) {
  common::data_module_phase_t m;
  m.utime = module::utime_now();
  m.module = self_.name();
  m.target = p.spec.name;
  m.phase = static_cast<std::int8_t>(p.phase);
  m.pid = p.pid;
  m.restarts = p.restarts;
  m.exit_status = p.exit_status;
  m.next_start_ms = -1;
  if (p.phase == Phase::Terminated && p.command != State::Terminate) {
    const auto left = std::chrono::duration_cast<Millis>(p.next_start - now()).count();
    m.next_start_ms = left < 0 ? 0 : static_cast<std::int32_t>(left);
  }
  m.command = static_cast<std::int8_t>(p.command);
  self_.lcm().publish(std::string(msgs::kDataModules.name), &m);
}

void Supervisor::set_phase(Proc& p, Phase ph) {
  if (p.phase == ph) return;
  p.phase = ph;
  publish(p);
  if (notifier_) notifier_->status(summary());
}

void Supervisor::launch(Proc& p) {
  std::map<std::string, std::string> extra;
  if (!self_.log_dir().empty()) extra[module::kLogDirEnv] = self_.log_dir().string();
  // The modules talk on the supervisor's bus unless their env says otherwise.
  if (!p.spec.env.count(msgs::kLcmUrlVariable)) extra[msgs::kLcmUrlVariable] = self_.lcm_url();
  try {
    p.pid = processes_.spawn(p.spec, extra);
  } catch (const std::system_error& e) {
    self_.errors().report(Severity::Error, ErrorType::Resource, e.code().value(),
                          p.spec.name + ": cannot start: " + e.what());
    p.next_start = now() + p.backoff.on_exit(Millis(0));
    set_phase(p, Phase::Terminated);
    return;
  }
  if (p.started_once) ++p.restarts;
  p.started_once = true;
  p.started = now();
  p.killed = false;
  self_.errors().report(Severity::Notice, ErrorType::Unknown, 0,
                        p.spec.name + ": started " + p.spec.path + " as pid " +
                            std::to_string(p.pid) +
                            (p.restarts ? " (restart " + std::to_string(p.restarts) + ")" : ""));
  set_phase(p, Phase::Starting);
}

void Supervisor::terminate(Proc& p, const std::string& why) {
  if (p.pid <= 0 || p.phase == Phase::Terminating) return;
  self_.errors().report(p.command == State::Terminate ? Severity::Notice : Severity::Warning,
                        ErrorType::Timeout, 0,
                        p.spec.name + " (pid " + std::to_string(p.pid) + "): " + why +
                            ": SIGTERM");
  // SIGCONT too: a stopped process would keep SIGTERM pending forever.
  processes_.signal_group(p.pid, SIGTERM);
  processes_.signal_group(p.pid, SIGCONT);
  p.kill_at = now() + cfg_.term_grace;
  set_phase(p, Phase::Terminating);
}

void Supervisor::on_announce(const common::data_state_t& m) {
  Proc* p = find(m.module);
  if (!p || p->pid <= 0) return;
  // An announcement from an older instance (or a stray copy started by hand)
  // must not keep a hung one alive.
  if (m.pid != 0 && m.pid != p->pid) return;
  p->last_announce = now();
  if (p->phase == Phase::Starting) set_phase(*p, Phase::Running);
}

void Supervisor::on_command(const common::cmd_state_t& m) {
  for (auto& p : procs_) {
    if (m.target != p.spec.name && m.target != "*") continue;
    const auto to = module::state_from_wire(m.state);
    if (!to || *to == State::Unknown) continue;
    const State before = p.command;
    p.command = *to;
    if (*to == State::Terminate) {
      if (p.pid > 0)
        terminate(p, "commanded TERMINATE by " + m.module);
      else
        set_phase(p, Phase::Down);
    } else if (before == State::Terminate && (p.phase == Phase::Down || p.phase == Phase::Terminated)) {
      // A module brought back by hand starts at once, without back-off.
      p.backoff.reset();
      self_.errors().report(Severity::Notice, ErrorType::Unknown, 0,
                            p.spec.name + ": commanded " + std::string(module::to_string(*to)) +
                                " by " + m.module + ": starting");
      launch(p);
    }
    publish(p);
  }
}

void Supervisor::reap() {
  while (const auto child = processes_.reap()) {
    const pid_t pid = child->pid;
    const int status = child->status;
    Proc* p = find(pid);
    if (!p) continue;  // not ours (or already forgotten)
    const int code = WIFEXITED(status) ? WEXITSTATUS(status) : 128 + WTERMSIG(status);
    const auto ran = std::chrono::duration_cast<Millis>(now() - p->started);
    p->exit_status = code;
    p->pid = 0;
    if (shut_down_ || p->command == State::Terminate) {
      self_.errors().report(Severity::Notice, ErrorType::Unknown, code,
                            p->spec.name + ": ended (" + module::describe_exit_code(code) +
                                "), kept down");
      set_phase(*p, Phase::Down);
      continue;
    }
    const Millis delay = p->backoff.on_exit(ran);
    p->next_start = now() + delay;
    self_.errors().report(Severity::Warning, ErrorType::Unknown, code,
                          p->spec.name + ": ended after " + ms_text(ran) + " (" +
                              module::describe_exit_code(code) + "), restart in " +
                              ms_text(delay));
    set_phase(*p, Phase::Terminated);
  }
}

void Supervisor::check() {
  if (shut_down_) return;
  const auto t = now();
  for (auto& p : procs_) {
    switch (p.phase) {
      case Phase::Down:
        break;
      case Phase::Starting:
        if (t - p.started > cfg_.startup_grace)
          terminate(p, "no state announcement " + ms_text(cfg_.startup_grace) + " after start");
        break;
      case Phase::Running:
        if (t - p.last_announce > cfg_.dead_after)
          terminate(p, "last state announcement " +
                           ms_text(std::chrono::duration_cast<Millis>(t - p.last_announce)) +
                           " ago");
        break;
      case Phase::Terminating:
        if (!p.killed && t >= p.kill_at) {
          self_.errors().report(Severity::Warning, ErrorType::Timeout, 0,
                                p.spec.name + " (pid " + std::to_string(p.pid) +
                                    "): still alive after SIGTERM: SIGKILL");
          processes_.signal_group(p.pid, SIGKILL);
          p.killed = true;
        }
        break;
      case Phase::Terminated:
        if (p.command != State::Terminate && t >= p.next_start) launch(p);
        break;
    }
  }
}

void Supervisor::shutdown() {
  if (shut_down_) return;
  shut_down_ = true;
  if (notifier_) notifier_->stopping();
  bool any = false;
  for (auto& p : procs_) {
    if (p.pid > 0) {
      processes_.signal_group(p.pid, SIGTERM);
      processes_.signal_group(p.pid, SIGCONT);
      any = true;
    }
  }
  // Wait for them, at most term_grace; SIGCHLD ends each wait at once.
  const auto deadline = now() + cfg_.term_grace;
  while (any) {
    reap();
    any = std::any_of(procs_.begin(), procs_.end(), [](const Proc& p) { return p.pid > 0; });
    const auto left = deadline - now();
    if (!any || left <= module::Duration::zero()) break;
    processes_.wait_for_exit(left);
  }
  for (auto& p : procs_) {
    if (p.pid > 0) {
      self_.errors().report(Severity::Warning, ErrorType::Timeout, 0,
                            p.spec.name + " (pid " + std::to_string(p.pid) +
                                "): still alive after SIGTERM: SIGKILL");
      processes_.signal_group(p.pid, SIGKILL);
    }
  }
  // SIGKILL cannot be refused: wait for each as long as it takes.
  while (std::any_of(procs_.begin(), procs_.end(), [](const Proc& p) { return p.pid > 0; })) {
    processes_.wait_for_exit(std::chrono::milliseconds(100));
    reap();
  }
}

}  // namespace advee::watchdog
