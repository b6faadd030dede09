// SPDX-License-Identifier: GPL-2.0
// Master-side CiA 402 power state machine of one axis: walks the drive from
// whatever state it reports to the requested one, one transition at a time,
// with a per-axis transition timeout, a rising edge for fault reset, and
// transition 16 (quick stop -> enabled) tried only if configured and dropped
// for good once the drive refuses it. Passive: statuswords come in through
// on_statusword(), controlwords go out through the sink.
#pragma once

#include <cstdint>
#include <functional>
#include <optional>
#include <system_error>

#include "advee/canopen/cia402.hpp"
#include "advee/canopen/clock.hpp"

namespace advee::canopen {

enum class AxisError {
  kTransitionTimeout = 1,  // the drive did not reach the next state in time
  kFault,                  // the drive stays in fault after fault reset
  kUnreachable,            // the target state cannot be commanded
  kCancelled,              // superseded by a newer request
  kModeTimeout,            // 0x6061 did not follow 0x6060
  kSetPointTimeout,        // no set-point acknowledge
  kHomingError,            // statusword bit 13 in homing mode
  kHomingTimeout,
  kNotReady,               // drive not booted / not enabled for this command
  kPdoMismatch,            // the device's PDO mapping is not what the driver needs
  kHeartbeatLost,
};
const std::error_category& axis_category();
inline std::error_code make_error_code(AxisError e) { return {static_cast<int>(e), axis_category()}; }

struct AxisConfig {
  Duration transition_timeout = std::chrono::milliseconds(500);
  bool try_transition_16 = false;
};

class Axis402 {
 public:
  using Done = std::function<void(std::error_code)>;
  using ControlwordSink = std::function<void(std::uint16_t)>;

  Axis402(AxisConfig cfg, NowFn now, ControlwordSink sink);

  void on_statusword(std::uint16_t sw);
  // Quick stop active is also satisfied by switch on disabled (a drive that
  // was not enabled has nothing to stop, and option codes 1-4 end there).
  void request(cia402::State target, Done done);
  void poll();
  std::optional<TimePoint> deadline() const;

  bool has_statusword() const { return sw_.has_value(); }
  std::uint16_t statusword() const { return sw_.value_or(0); }
  cia402::State state() const;
  std::uint16_t controlword() const { return cw_; }
  // Changes mode-specific bits (4-6, 8, 9) and sends the word if it changed.
  void set_bits(std::uint16_t mask, std::uint16_t value);
  bool transition_16_usable() const { return use16_; }
  bool busy() const { return target_.has_value(); }

 private:
  void advance();
  void finish(std::error_code ec);
  void send(std::uint16_t w);

  AxisConfig cfg_;
  NowFn now_;
  ControlwordSink sink_;
  std::optional<std::uint16_t> sw_;
  std::uint16_t cw_ = 0;
  bool use16_;
  std::optional<cia402::State> target_;
  std::optional<cia402::Step> step_;
  TimePoint step_deadline_{};
  int fault_resets_ = 0;
  Done done_;
};

}  // namespace advee::canopen

template <>
struct std::is_error_code_enum<advee::canopen::AxisError> : std::true_type {};
