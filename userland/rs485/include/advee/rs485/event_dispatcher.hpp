// SPDX-License-Identifier: GPL-2.0
// The subscriber list behind Transport::subscribe(): Bus and FakeTransport
// share it. dispatch() and close() come from one producer thread at a time.
#pragma once

#include <cstdint>
#include <map>
#include <memory>
#include <mutex>
#include <system_error>
#include <thread>

#include "advee/rs485/transport.hpp"

namespace advee::rs485 {

class EventDispatcher {
 public:
  EventDispatcher();
  ~EventDispatcher();
  EventDispatcher(const EventDispatcher&) = delete;
  EventDispatcher& operator=(const EventDispatcher&) = delete;

  Subscription subscribe(EventHandler on_event, ClosedHandler on_closed);
  // Calls every subscriber's on_event (in subscription order).
  void dispatch(const Frame& frame);
  // Calls every subscriber's on_closed once; later subscribers get it at once.
  void close(std::error_code why);
  bool closed() const;
  std::size_t subscribers() const;

 private:
  struct State;
  std::shared_ptr<State> state_;
};

}  // namespace advee::rs485
