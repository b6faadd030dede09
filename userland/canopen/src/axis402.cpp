// SPDX-License-Identifier: GPL-2.0
#include "advee/canopen/axis402.hpp"

namespace advee::canopen {

using cia402::State;

namespace {
class AxisCategory final : public std::error_category {
 public:
  const char* name() const noexcept override { return "cia402-axis"; }
  std::string message(int ev) const override {
    switch (static_cast<AxisError>(ev)) {
      case AxisError::kTransitionTimeout: return "drive did not make the state transition in time";
      case AxisError::kFault: return "drive stays in fault after fault reset";
      case AxisError::kUnreachable: return "requested state cannot be commanded from the drive's state";
      case AxisError::kCancelled: return "request superseded";
      case AxisError::kModeTimeout: return "modes of operation display (0x6061) did not follow 0x6060";
      case AxisError::kSetPointTimeout: return "drive did not acknowledge the set-point";
      case AxisError::kHomingError: return "drive reports a homing error";
      case AxisError::kHomingTimeout: return "homing did not finish in time";
      case AxisError::kNotReady: return "drive is not ready for this command";
      case AxisError::kPdoMismatch: return "device PDO mapping is not what the driver needs";
      case AxisError::kHeartbeatLost: return "drive heartbeat lost";
    }
    return "unknown axis error";
  }
};
}  // namespace

const std::error_category& axis_category() {
  static const AxisCategory c;
  return c;
}

Axis402::Axis402(AxisConfig cfg, NowFn now, ControlwordSink sink)
    : cfg_(cfg), now_(std::move(now)), sink_(std::move(sink)), use16_(cfg.try_transition_16) {}

State Axis402::state() const { return sw_ ? cia402::decode(*sw_) : State::kNotReadyToSwitchOn; }

void Axis402::send(std::uint16_t w) {
  cw_ = w;
  sink_(w);
}

void Axis402::set_bits(std::uint16_t mask, std::uint16_t value) {
  const auto w = static_cast<std::uint16_t>((cw_ & ~mask) | (value & mask));
  if (w != cw_) send(w);
}

void Axis402::on_statusword(std::uint16_t sw) {
  const bool changed = !sw_ || cia402::decode(*sw_) != cia402::decode(sw);
  sw_ = sw;
  if (changed && target_) {
    step_.reset();
    advance();
  }
}

void Axis402::request(State target, Done done) {
  if (done_) {
    auto old = std::move(done_);
    done_ = nullptr;
    old(make_error_code(AxisError::kCancelled));
  }
  target_ = target;
  done_ = std::move(done);
  step_.reset();
  fault_resets_ = 0;
  advance();
}

void Axis402::finish(std::error_code ec) {
  target_.reset();
  step_.reset();
  auto done = std::move(done_);
  done_ = nullptr;
  if (done) done(ec);
}

void Axis402::advance() {
  if (!target_) return;
  if (!sw_) {
    // No statusword yet (TPDO not flowing): wait one transition timeout for it.
    if (!step_) {
      step_ = cia402::Step{cia402::Command::kDisableVoltage, 0, State::kNotReadyToSwitchOn};
      step_deadline_ = now_() + cfg_.transition_timeout;
    }
    return;
  }
  const State s = state();
  if (s == *target_ || (*target_ == State::kQuickStopActive && s == State::kSwitchOnDisabled))
    return finish({});
  auto step = cia402::next_step(s, *target_, use16_);
  if (!step) {
    if (s == State::kNotReadyToSwitchOn || s == State::kFaultReactionActive) {
      // The drive moves on by itself; give it one transition timeout.
      if (!step_) {
        step_ = cia402::Step{cia402::Command::kDisableVoltage, 0, s};
        step_deadline_ = now_() + cfg_.transition_timeout;
      }
      return;
    }
    if (*target_ == State::kQuickStopActive) {
      // Not enabled: disabling the voltage is the stop.
      step = cia402::next_step(s, State::kSwitchOnDisabled, false);
      if (!step) return finish(make_error_code(AxisError::kUnreachable));
    } else {
      return finish(make_error_code(AxisError::kUnreachable));
    }
  }
  if (step->command == cia402::Command::kFaultReset) {
    if (fault_resets_ >= 2) return finish(make_error_code(AxisError::kFault));
    ++fault_resets_;
    // Fault reset acts on the rising edge of bit 7.
    if (cw_ & cia402::cw::kFaultReset) send(static_cast<std::uint16_t>(cw_ & ~cia402::cw::kFaultReset));
  }
  step_ = step;
  step_deadline_ = now_() + cfg_.transition_timeout;
  send(cia402::apply(step->command, cw_));
}

void Axis402::poll() {
  if (!target_ || !step_ || now_() < step_deadline_) return;
  if (step_->transition == 16) {
    // The drive does not implement the optional transition 16: go round via
    // switch on disabled from now on.
    use16_ = false;
    step_.reset();
    return advance();
  }
  if (step_->command == cia402::Command::kFaultReset) {
    step_.reset();
    return advance();  // one more edge; advance() gives up after two
  }
  finish(make_error_code(AxisError::kTransitionTimeout));
}

std::optional<TimePoint> Axis402::deadline() const {
  if (!target_ || !step_) return std::nullopt;
  return step_deadline_;
}

}  // namespace advee::canopen
