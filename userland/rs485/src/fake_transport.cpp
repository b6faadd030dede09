// SPDX-License-Identifier: GPL-2.0
#include "advee/rs485/fake_transport.hpp"

namespace advee::rs485 {

void FakeTransport::set_responder(Responder responder) {
  std::lock_guard lock(mutex_);
  responder_ = std::move(responder);
}

Result FakeTransport::transact(const Request& request) {
  Responder responder;
  {
    std::lock_guard lock(mutex_);
    requests_.push_back(request);
    responder = responder_;
  }
  if (!request.expects_response()) return ack();
  if (!responder) return fail(Outcome::timeout);
  return responder(request);
}

Subscription FakeTransport::subscribe(EventHandler on_event, ClosedHandler on_closed) {
  return events_.subscribe(std::move(on_event), std::move(on_closed));
}

std::vector<Request> FakeTransport::requests() const {
  std::lock_guard lock(mutex_);
  return requests_;
}

void FakeTransport::clear_requests() {
  std::lock_guard lock(mutex_);
  requests_.clear();
}

Result FakeTransport::ack(std::vector<std::uint8_t> data) {
  Result r;
  r.flags = response_flag::kAck;
  r.data = std::move(data);
  r.attempts = 1;
  return r;
}

Result FakeTransport::fail(Outcome outcome, std::vector<std::uint8_t> data) {
  Result r;
  r.error = make_error_code(outcome);
  if (outcome == Outcome::unknown_instruction) r.flags = response_flag::kUnknownInstruction;
  if (outcome == Outcome::device_error) r.flags = response_flag::kDeviceError;
  r.data = std::move(data);
  r.attempts = 1;
  return r;
}

}  // namespace advee::rs485
