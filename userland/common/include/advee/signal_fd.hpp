// SPDX-License-Identifier: GPL-2.0
// Signals as a file descriptor, the one wrapper of the stack (modules,
// the CANopen loop, advee-rs485ctl, advee-rs485-sim): the listed signals are blocked in
// the calling thread (create this before any other thread, LCM's receive
// thread included, so that every thread inherits the mask) and read from a
// non-blocking signalfd. Destruction discards the signals still pending in
// the set and restores the previous mask: unblocked, a SIGTERM that arrived
// while the program was already ending would kill it and replace its exit
// status with 143.
#pragma once

#include <pthread.h>
#include <signal.h>
#include <sys/signalfd.h>
#include <unistd.h>

#include <cerrno>
#include <initializer_list>
#include <optional>
#include <system_error>
#include <vector>

#include "advee/unique_fd.hpp"

namespace advee {

class SignalFd {
 public:
  // Throws std::system_error.
  explicit SignalFd(std::initializer_list<int> signals) : SignalFd(signals.begin(), signals.end()) {}
  explicit SignalFd(const std::vector<int>& signals) : SignalFd(signals.begin(), signals.end()) {}
  template <typename It>
  SignalFd(It first, It last) {
    sigset_t set;
    sigemptyset(&set);
    for (; first != last; ++first) sigaddset(&set, *first);
    if (const int e = pthread_sigmask(SIG_BLOCK, &set, &old_mask_))
      throw std::system_error(e, std::generic_category(), "pthread_sigmask");
    fd_.reset(::signalfd(-1, &set, SFD_NONBLOCK | SFD_CLOEXEC));
    if (!fd_) {
      const int e = errno;
      pthread_sigmask(SIG_SETMASK, &old_mask_, nullptr);
      throw std::system_error(e, std::generic_category(), "signalfd");
    }
  }
  ~SignalFd() {
    while (read()) {
    }
    fd_.reset();
    pthread_sigmask(SIG_SETMASK, &old_mask_, nullptr);
  }
  SignalFd(const SignalFd&) = delete;
  SignalFd& operator=(const SignalFd&) = delete;

  int fd() const { return fd_.get(); }
  // The next pending signal, nullopt when none (never blocks).
  std::optional<signalfd_siginfo> read() {
    signalfd_siginfo si;
    if (::read(fd_.get(), &si, sizeof si) != static_cast<ssize_t>(sizeof si)) return std::nullopt;
    return si;
  }

 private:
  sigset_t old_mask_;
  UniqueFd fd_;
};

}  // namespace advee
