// SPDX-License-Identifier: GPL-2.0
// In-process CAN bus for unit tests and simulations: every frame sent on one
// port is delivered to all other ports. Delivery is queued and happens in
// deliver(), so a reply sent from inside a receive callback never re-enters
// the sender (the same ordering a real bus gives).
#pragma once

#include <cstddef>
#include <deque>
#include <functional>
#include <vector>

#include "advee/canopen/frame.hpp"

namespace advee::canopen {

class VirtualBus {
 public:
  using Receiver = std::function<void(const CanFrame&)>;

  // Returns the port number.
  std::size_t attach(Receiver rx);
  FrameSender sender(std::size_t port);
  // Delivers queued frames (and the frames their receivers send) until the
  // bus is idle or `limit` frames were delivered. Returns how many.
  std::size_t deliver(std::size_t limit = 100000);

  // Every frame ever sent, in bus order.
  const std::vector<CanFrame>& log() const { return log_; }
  void clear_log() { log_.clear(); }
  // While set, frames sent from `port` vanish (a node that went silent).
  void mute(std::size_t port, bool muted);

 private:
  struct Pending {
    std::size_t from;
    CanFrame frame;
  };
  std::vector<Receiver> ports_;
  std::vector<bool> muted_;
  std::deque<Pending> queue_;
  std::vector<CanFrame> log_;
};

}  // namespace advee::canopen
