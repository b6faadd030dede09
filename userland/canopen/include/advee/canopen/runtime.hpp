// SPDX-License-Identifier: GPL-2.0
// Production wiring: the passive Master fed by a CanPort on an EventLoop,
// with the loop's timerfd armed at the master's next deadline; plus a
// signalfd helper for daemons. Everything here is owned RAII.
#pragma once

#include <csignal>
#include <functional>
#include <initializer_list>
#include <memory>
#include <string>

#include "advee/canopen/can_port.hpp"
#include "advee/canopen/event_loop.hpp"
#include "advee/canopen/master.hpp"
#include "advee/signal_fd.hpp"

namespace advee::canopen {

class MasterRuntime {
 public:
  // on_error gets the controller's error frames (state changes, restarts);
  // without one, state changes are printed to stderr.
  MasterRuntime(EventLoop& loop, const std::string& ifname, MasterConfig cfg, CanPort::ErrorHandler on_error = nullptr);
  Master& master() { return master_; }
  CanPort& port() { return *port_; }
  EventLoop& loop() { return loop_; }

 private:
  EventLoop& loop_;
  std::unique_ptr<CanPort> port_;
  Master master_;
};

// Blocks the given signals in the calling thread (before other threads
// start, so that they inherit the mask) and delivers them through the loop;
// destruction restores the mask (advee/signal_fd.hpp).
class SignalHandler {
 public:
  SignalHandler(EventLoop& loop, std::initializer_list<int> signals, std::function<void(int)> on_signal);
  ~SignalHandler();
  SignalHandler(const SignalHandler&) = delete;
  SignalHandler& operator=(const SignalHandler&) = delete;

 private:
  EventLoop& loop_;
  SignalFd fd_;
  std::function<void(int)> on_signal_;
};

}  // namespace advee::canopen
