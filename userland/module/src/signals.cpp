// SPDX-License-Identifier: GPL-2.0
#include "advee/module/signals.hpp"

#include <pthread.h>
#include <unistd.h>

#include <cerrno>
#include <system_error>

namespace advee::module {

SignalFd::SignalFd(const std::vector<int>& signals) {
  sigset_t set;
  sigemptyset(&set);
  for (int s : signals) sigaddset(&set, s);
  if (int e = pthread_sigmask(SIG_BLOCK, &set, &old_mask_))
    throw std::system_error(e, std::generic_category(), "pthread_sigmask");
  fd_.reset(::signalfd(-1, &set, SFD_NONBLOCK | SFD_CLOEXEC));
  if (!fd_) {
    const int e = errno;
    pthread_sigmask(SIG_SETMASK, &old_mask_, nullptr);
    throw std::system_error(e, std::generic_category(), "signalfd");
  }
}

SignalFd::~SignalFd() {
  // Consume what is still pending: unblocked, a SIGTERM that arrived while
  // the module was already ending would kill the process and replace its
  // exit code with 143.
  while (read()) {
  }
  fd_.reset();
  pthread_sigmask(SIG_SETMASK, &old_mask_, nullptr);
}

std::optional<signalfd_siginfo> SignalFd::read() {
  signalfd_siginfo si;
  if (::read(fd_.get(), &si, sizeof si) != sizeof si) return std::nullopt;
  return si;
}

}  // namespace advee::module
