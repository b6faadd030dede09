// SPDX-License-Identifier: GPL-2.0
#include "advee/canopen/runtime.hpp"

#include <sys/epoll.h>
#include <sys/signalfd.h>

#include <cerrno>
#include <cstdio>
#include <system_error>

namespace advee::canopen {

namespace {
void print_state(const CanErrorInfo& e) {
  if (e.state) std::fprintf(stderr, "canopen: controller %s\n", std::string(to_string(*e.state)).c_str());
}
}  // namespace

MasterRuntime::MasterRuntime(EventLoop& loop, const std::string& ifname, MasterConfig cfg, CanPort::ErrorHandler on_error)
    : loop_(loop),
      port_(std::make_unique<CanPort>(
          loop, CanSocket::open(ifname), [this](const CanFrame& f) { master_.handle(f); },
          on_error ? std::move(on_error) : CanPort::ErrorHandler(print_state))),
      master_(cfg, port_->sender(), system_monotonic_clock()) {
  loop_.add_timer_source([this] { return master_.next_deadline(); }, [this] { master_.poll(); });
}

SignalHandler::SignalHandler(EventLoop& loop, std::initializer_list<int> signals, std::function<void(int)> on_signal)
    : loop_(loop), fd_(signals), on_signal_(std::move(on_signal)) {
  loop_.add_fd(fd_.fd(), EPOLLIN, [this](std::uint32_t) {
    while (const auto si = fd_.read()) on_signal_(static_cast<int>(si->ssi_signo));
  });
}

SignalHandler::~SignalHandler() { loop_.remove_fd(fd_.fd()); }

}  // namespace advee::canopen
