// SPDX-License-Identifier: GPL-2.0
// In-memory Transport for unit tests and in-process simulations: a responder
// function answers every transact(); inject_event() delivers an event frame
// to the subscribers on the calling thread. Records every request.
#pragma once

#include <functional>
#include <mutex>
#include <vector>

#include "advee/rs485/event_dispatcher.hpp"
#include "advee/rs485/transport.hpp"

namespace advee::rs485 {

class FakeTransport final : public Transport {
 public:
  using Responder = std::function<Result(const Request&)>;

  FakeTransport() = default;
  explicit FakeTransport(Responder responder) : responder_(std::move(responder)) {}

  void set_responder(Responder responder);
  // Without a responder every transaction ends with Outcome::timeout.
  Result transact(const Request& request) override;
  Subscription subscribe(EventHandler on_event, ClosedHandler on_closed = {}) override;

  void inject_event(const Frame& frame) { events_.dispatch(frame); }
  void close_events(std::error_code why) { events_.close(why); }

  std::vector<Request> requests() const;
  void clear_requests();

  // Helpers for responders: an ACK with data, and a failed outcome.
  static Result ack(std::vector<std::uint8_t> data = {});
  static Result fail(Outcome outcome, std::vector<std::uint8_t> data = {});

 private:
  mutable std::mutex mutex_;
  Responder responder_;
  std::vector<Request> requests_;
  EventDispatcher events_;
};

}  // namespace advee::rs485
