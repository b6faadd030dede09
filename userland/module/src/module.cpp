// SPDX-License-Identifier: GPL-2.0
#include "advee/module/module.hpp"

#include <poll.h>
#include <sys/prctl.h>
#include <unistd.h>

#include <cerrno>
#include <cstdlib>
#include <iostream>
#include <lcm/lcm-cpp.hpp>
#include <system_error>

#include "advee/module/log_dir.hpp"
#include "advee/module/time.hpp"
#include "advee/msgs/bus.hpp"
#include "advee/msgs/channels.hpp"
#include "common/cmd_state_t.hpp"
#include "common/data_state_t.hpp"

namespace advee::module {
namespace {

std::vector<int> blocked_signals(const ModuleOptions& o) {
  std::vector<int> s{SIGTERM, SIGINT, SIGHUP};
  s.insert(s.end(), o.extra_signals.begin(), o.extra_signals.end());
  return s;
}

void on_cmd_state(const lcm::ReceiveBuffer*, const std::string&, const common::cmd_state_t* m,
                  Module* self);

}  // namespace

Module::Module(ModuleOptions opts) : Module(std::move(opts), std::make_unique<MonotonicTimers>(), nullptr) {}

Module::Module(ModuleOptions opts, TimerSource& timers) : Module(std::move(opts), nullptr, &timers) {}

Module::Module(ModuleOptions opts, std::unique_ptr<TimerSource> own, TimerSource* external)
    : opts_(std::move(opts)),
      signals_(blocked_signals(opts_)),
      own_timers_(std::move(own)),
      timers_(external ? *external : *own_timers_) {
  // No transparent huge pages for a module (Debian's x86 kernels have THP
  // "always"): a thread's 8 MB stack otherwise gets a 2 MB page on its first
  // touch, a quarter of the whole stack's memory budget (bench/daemons.sh,
  // docs/daemons.md "Resource use"). Process-wide, also for threads started
  // before, inherited by children; a kernel without THP (the TS-7800's) just
  // keeps the flag.
  prctl(PR_SET_THP_DISABLE, 1, 0, 0, 0);
  try {
    const auto url = msgs::bus_url(opts_.lcm_url, "module.lcm_url");
    lcm_url_ = url.url;
    lcm_ = msgs::open_bus(url);
  } catch (const msgs::BusUnavailable& e) {
    throw ModuleExit(ExitKind::Resource, 1, e.what());
  }
  errors_ = std::make_unique<ErrorReporter>(opts_.name, opts_.errors, lcm_.get());
  try {
    if (const char* d = std::getenv(kLogDirEnv); d && *d)
      log_dir_ = d;
    else if (!opts_.log_root.empty())
      log_dir_ = create_run_log_dir(opts_.log_root);
    if (!log_dir_.empty()) errors_->set_log_file((log_dir_ / (opts_.name + ".log")).string());
  } catch (const std::exception& e) {
    throw ModuleExit(ExitKind::Resource, 2, std::string("log directory: ") + e.what());
  }
  lcm_->subscribeFunction(std::string(msgs::kCmdState.name), &on_cmd_state, this);
  announce_timer_ = timers_.every(opts_.announce_period, [this] { announce(); });
}

Module::~Module() = default;

namespace {
// Runs inside LCM's C dispatch: copy the message and act on the loop proper,
// so that state hooks may throw ModuleExit without unwinding through C frames.
void on_cmd_state(const lcm::ReceiveBuffer*, const std::string&, const common::cmd_state_t* m,
                  Module* self) {
  if (m->target != self->name() && m->target != "*") return;
  self->post([self, m = *m] { self->obey(m); });
}
}  // namespace

void Module::obey(const common::cmd_state_t& m) {
  const auto to = state_from_wire(m.state);
  if (!to || *to == State::Unknown) {
    errors_->report(Severity::Warning, ErrorType::Unknown, m.state,
                    "CM_CMD_STATE from " + m.module + ": no such state " + std::to_string(m.state));
    return;
  }
  if (*to == state_) {
    announce();  // already there: confirm at once
    return;
  }
  request_state(*to, m.manual, "commanded by " + m.module);
}

void Module::on_state_change(std::function<void(State, State)> fn) {
  state_hooks_.push_back(std::move(fn));
}

void Module::every(std::chrono::nanoseconds period, std::function<void()> fn, bool only_in_run) {
  periodics_.push_back(timers_.every(period, [this, fn = std::move(fn), only_in_run] {
    if (!only_in_run || state_ == State::Run) fn();
  }));
}

void Module::watch_fd(int fd, std::function<void()> fn) { fds_.emplace_back(fd, std::move(fn)); }

void Module::on_signal(int signo, std::function<void(const signalfd_siginfo&)> fn) {
  signal_handlers_.emplace_back(signo, std::move(fn));
}

void Module::post(std::function<void()> fn) {
  {
    std::lock_guard lock(post_mutex_);
    posted_.push_back(std::move(fn));
  }
  waker_.notify();
}

bool Module::request_state(State to, bool manual, std::string_view why) {
  const State from = state_;
  if (!transition_allowed(from, to, manual)) {
    const bool manual_needed = transition(from, to) == Transition::ManualOnly;
    errors_->report(Severity::Notice, ErrorType::Unknown, 0,
                    "refused " + std::string(to_string(from)) + " -> " +
                        std::string(to_string(to)) + " (" + std::string(why) + ")" +
                        (manual_needed ? ": needs a manual command" : ""));
    return false;
  }
  state_ = to;
  errors_->report(Severity::Notice, ErrorType::Unknown, 0,
                  std::string(to_string(from)) + " -> " + std::string(to_string(to)) + " (" +
                      std::string(why) + ")");
  for (auto& h : state_hooks_) h(from, to);
  announce();
  return true;
}

void Module::announce() {
  common::data_state_t m;
  m.utime = utime_now();
  m.module = opts_.name;
  m.state = static_cast<std::int8_t>(state_);
  m.pid = static_cast<std::int32_t>(::getpid());
  lcm_->publish(std::string(msgs::kDataState.name), &m);
}

void Module::handle_signal(const signalfd_siginfo& si) {
  const int signo = static_cast<int>(si.ssi_signo);
  for (auto& [s, fn] : signal_handlers_)
    if (s == signo) return fn(si);
  if (signo == SIGTERM || signo == SIGINT || signo == SIGHUP)
    request_state(State::Terminate, true, std::string("signal ") + sigabbrev_np(signo));
}

bool Module::run_once(std::chrono::milliseconds max_wait) {
  if (state_ == State::Terminate) return false;
  std::vector<pollfd> pfds;
  pfds.push_back({signals_.fd(), POLLIN, 0});
  pfds.push_back({lcm_->getFileno(), POLLIN, 0});
  pfds.push_back({waker_.fd(), POLLIN, 0});
  pfds.push_back({timers_.fd(), POLLIN, 0});
  for (auto& [fd, fn] : fds_) pfds.push_back({fd, POLLIN, 0});
  const int n = ::poll(pfds.data(), pfds.size(), static_cast<int>(max_wait.count()));
  if (n < 0) {
    if (errno == EINTR) return true;
    throw std::system_error(errno, std::generic_category(), "poll");
  }
  auto ready = [&](std::size_t i) {
    return state_ != State::Terminate && (pfds[i].revents & (POLLIN | POLLERR | POLLHUP));
  };
  if (ready(0))
    while (auto si = signals_.read()) handle_signal(*si);
  if (ready(1)) lcm_->handleTimeout(0);
  if (ready(2)) {
    waker_.consume();
    std::vector<std::function<void()>> work;
    {
      std::lock_guard lock(post_mutex_);
      work.swap(posted_);
    }
    for (auto& fn : work) fn();
  }
  if (ready(3)) timers_.dispatch();  // the announcement and every() jobs
  for (std::size_t k = 0; k < fds_.size(); ++k)
    if (ready(4 + k)) fds_[k].second();
  return state_ != State::Terminate;
}

int Module::run() {
  try {
    if (state_ == State::Init) request_state(opts_.start_state, false, "initialised");
    while (run_once(std::chrono::milliseconds(-1))) {
    }
    return 0;
  } catch (const ModuleExit& e) {
    errors_->report(Severity::Error, ErrorType::Unknown, e.code(), e.what(), true);
    state_ = State::Terminate;
    announce();
    return e.code();
  }
}

int guarded_main(std::string_view module_name, const std::function<int()>& body) {
  const std::string who(module_name);
  try {
    return body();
  } catch (const ModuleExit& e) {
    std::cerr << who << ": " << e.what() << " (" << describe_exit_code(e.code()) << ")\n";
    return e.code();
  } catch (const ConfigError& e) {
    std::cerr << who << ": configuration: " << e.what() << "\n";
    return exit_code(ExitKind::Other, 1);
  } catch (const std::system_error& e) {
    std::cerr << who << ": " << e.what() << "\n";
    return exit_code(ExitKind::Resource, 1);
  } catch (const std::exception& e) {
    std::cerr << who << ": " << e.what() << "\n";
    return exit_code(ExitKind::Other, 2);
  }
}

}  // namespace advee::module
