// SPDX-License-Identifier: GPL-2.0
#include "advee/canopen/virtual_bus.hpp"

namespace advee::canopen {

std::size_t VirtualBus::attach(Receiver rx) {
  ports_.push_back(std::move(rx));
  muted_.push_back(false);
  return ports_.size() - 1;
}

FrameSender VirtualBus::sender(std::size_t port) {
  return [this, port](const CanFrame& f) {
    if (muted_[port]) return;
    log_.push_back(f);
    queue_.push_back({port, f});
  };
}

std::size_t VirtualBus::deliver(std::size_t limit) {
  std::size_t n = 0;
  while (!queue_.empty() && n < limit) {
    Pending p = queue_.front();
    queue_.pop_front();
    for (std::size_t i = 0; i < ports_.size(); ++i)
      if (i != p.from && ports_[i]) ports_[i](p.frame);
    ++n;
  }
  return n;
}

void VirtualBus::mute(std::size_t port, bool muted) { muted_[port] = muted; }

}  // namespace advee::canopen
