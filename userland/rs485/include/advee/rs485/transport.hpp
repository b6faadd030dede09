// SPDX-License-Identifier: GPL-2.0
// The abstract bus a device driver talks to. Bus implements it over the
// n_rs485 line discipline; FakeTransport (fake_transport.hpp) in memory, so
// that drivers are tested without a kernel.
#pragma once

#include <chrono>
#include <cstdint>
#include <functional>
#include <memory>
#include <optional>
#include <system_error>
#include <utility>
#include <vector>

#include "advee/registration.hpp"
#include "advee/rs485/error.hpp"
#include "advee/rs485/protocol.hpp"

namespace advee::rs485 {

// Per-call overrides of the bus configuration; unset = the bus default.
// (Constructors rather than an aggregate: designated initialisers with
// fields left out trip -Wmissing-field-initializers under -Werror.)
struct CallOptions {
  CallOptions() = default;
  CallOptions(std::optional<std::chrono::microseconds> timeout_, std::optional<unsigned> retries_ = {})
      : timeout(timeout_), retries(retries_) {}

  std::optional<std::chrono::microseconds> timeout;  // response timeout, 100 us .. 10 s
  std::optional<unsigned> retries;                    // retries after a failure, 0..16
};

struct Request {
  Request() = default;
  Request(std::uint8_t addr_, std::uint8_t instr_, std::vector<std::uint8_t> data_ = {},
          CallOptions options_ = {})
      : addr(addr_), instr(instr_), data(std::move(data_)), options(options_) {}

  std::uint8_t addr = 0;   // 0x00..0xFE, or kBroadcast (no response)
  std::uint8_t instr = 0;
  std::vector<std::uint8_t> data;
  CallOptions options;
  bool no_ack = false;     // NOACK: the node executes and sends no response

  // A request that gets no response: Result is OK once it is on the wire.
  bool expects_response() const { return addr != kBroadcast && !no_ack; }
};

// Outcome of transact(): error is empty on OK. For UNKINSTR/DEVERR, flags and
// data hold what the node sent (DEVERR data may describe the failure).
struct Result {
  std::error_code error;
  std::uint8_t flags = 0;           // response flags (0 if no response)
  std::vector<std::uint8_t> data;   // response data
  unsigned attempts = 0;            // requests sent (1 + retries used)

  bool ok() const { return !error; }
  explicit operator bool() const { return ok(); }
};

// Event frames (FLAGS has EVENT; also responses nobody waited for) are
// delivered to every subscriber, on the transport's event thread.
using EventHandler = std::function<void(const Frame&)>;
// Called once when event delivery ends for good: hangup, detach, or a read
// error (the error_code says which). Not called when the transport is destroyed.
using ClosedHandler = std::function<void(std::error_code)>;

// Keeps a subscription alive; destroying or reset()ting it unsubscribes.
// After reset() returns, the handler is not running and will not run again
// (unless reset() is called from within the handler itself, which is allowed).
using Subscription = advee::Registration;

class Transport {
 public:
  virtual ~Transport() = default;

  // One request/response transaction (thread-safe; the bus serialises them).
  virtual Result transact(const Request& request) = 0;

  // Event frames to `on_event` until the Subscription goes. Handlers run on
  // one event thread, one at a time; keep them short (no transact() from a
  // handler of the same transport is needed, but it is allowed).
  virtual Subscription subscribe(EventHandler on_event, ClosedHandler on_closed = {}) = 0;

 protected:
  Transport() = default;
  Transport(const Transport&) = delete;
  Transport& operator=(const Transport&) = delete;
};

}  // namespace advee::rs485
