// SPDX-License-Identifier: GPL-2.0
// Signals as a file descriptor: the listed signals are blocked in the calling
// thread (create this before any other thread, LCM's receive thread included,
// so that every thread inherits the mask) and read from a signalfd.
// Destruction discards the signals still pending in the set and restores
// the previous mask.
#pragma once

#include <signal.h>
#include <sys/signalfd.h>

#include <initializer_list>
#include <optional>
#include <vector>

#include "advee/unique_fd.hpp"

namespace advee::module {

class SignalFd {
 public:
  explicit SignalFd(const std::vector<int>& signals);  // throws std::system_error
  ~SignalFd();
  SignalFd(const SignalFd&) = delete;
  SignalFd& operator=(const SignalFd&) = delete;

  int fd() const { return fd_.get(); }
  // The next pending signal, nullopt when none (never blocks).
  std::optional<signalfd_siginfo> read();

 private:
  sigset_t old_mask_;
  UniqueFd fd_;
};

}  // namespace advee::module
