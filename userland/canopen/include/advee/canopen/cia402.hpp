// SPDX-License-Identifier: GPL-2.0
// CiA 402 device control: statusword decoder, command table (set/reset masks
// on the controlword) and the path through the power state machine
// (canopen-notes.md §3.9). Pure functions, shared by the master's axis
// controller and the drive simulator.
#pragma once

#include <cstdint>
#include <optional>
#include <string_view>

namespace advee::canopen::cia402 {

enum class State {
  kNotReadyToSwitchOn,
  kSwitchOnDisabled,
  kReadyToSwitchOn,
  kSwitchedOn,
  kOperationEnabled,
  kQuickStopActive,
  kFaultReactionActive,
  kFault,
};

enum class Command {
  kShutdown,          // transitions 2, 6, 8
  kSwitchOn,          // 3
  kEnableOperation,   // 4, 16
  kDisableVoltage,    // 7, 9, 10, 12
  kQuickStop,         // 7, 10, 11
  kDisableOperation,  // 5
  kFaultReset,        // 15 (rising edge of bit 7)
};

enum class Mode : std::int8_t {
  kNone = 0,
  kProfilePosition = 1,
  kVelocity = 2,
  kProfileVelocity = 3,
  kProfileTorque = 4,
  kHoming = 6,
  kInterpolatedPosition = 7,
  kCyclicSyncPosition = 8,
  kCyclicSyncVelocity = 9,
  kCyclicSyncTorque = 10,
};

namespace cw {
inline constexpr std::uint16_t kSwitchOn = 1u << 0;
inline constexpr std::uint16_t kEnableVoltage = 1u << 1;
inline constexpr std::uint16_t kQuickStop = 1u << 2;  // active low
inline constexpr std::uint16_t kEnableOperation = 1u << 3;
inline constexpr std::uint16_t kNewSetPoint = 1u << 4;     // pp
inline constexpr std::uint16_t kHomingStart = 1u << 4;     // hm
inline constexpr std::uint16_t kChangeImmediately = 1u << 5;  // pp
inline constexpr std::uint16_t kRelative = 1u << 6;        // pp
inline constexpr std::uint16_t kFaultReset = 1u << 7;
inline constexpr std::uint16_t kHalt = 1u << 8;
}  // namespace cw

namespace sw {
inline constexpr std::uint16_t kReadyToSwitchOn = 1u << 0;
inline constexpr std::uint16_t kSwitchedOn = 1u << 1;
inline constexpr std::uint16_t kOperationEnabled = 1u << 2;
inline constexpr std::uint16_t kFault = 1u << 3;
inline constexpr std::uint16_t kVoltageEnabled = 1u << 4;
inline constexpr std::uint16_t kQuickStop = 1u << 5;  // 0 = quick stop active
inline constexpr std::uint16_t kSwitchOnDisabled = 1u << 6;
inline constexpr std::uint16_t kWarning = 1u << 7;
inline constexpr std::uint16_t kRemote = 1u << 9;
inline constexpr std::uint16_t kTargetReached = 1u << 10;
inline constexpr std::uint16_t kInternalLimit = 1u << 11;
inline constexpr std::uint16_t kSetPointAcknowledge = 1u << 12;  // pp
inline constexpr std::uint16_t kSpeedZero = 1u << 12;            // pv
inline constexpr std::uint16_t kHomingAttained = 1u << 12;       // hm
inline constexpr std::uint16_t kFollowingError = 1u << 13;       // pp
inline constexpr std::uint16_t kHomingError = 1u << 13;          // hm
}  // namespace sw

State decode(std::uint16_t statusword);
// The state bits (0-6) a drive reports in `s`; bit 4 (voltage enabled) is set
// in the powered states.
std::uint16_t statusword_bits(State s);
// Applies the command's set/reset masks to bits 0-3 and 7 and keeps the rest
// (halt, mode-specific bits).
std::uint16_t apply(Command c, std::uint16_t controlword);
// Which command a controlword expresses for a drive in state `s` (the
// drive's view; fault reset needs the previous word to see the edge).
std::optional<Command> command_in(std::uint16_t controlword, std::uint16_t previous, State s);

struct Step {
  Command command;
  int transition;  // CiA 402 transition number
  State expect;
};
// Next step from `from` toward `to`, never jumping a state. nullopt if
// `from` == `to`, if the drive must move on its own (not ready, fault
// reaction) or if `to` cannot be commanded (fault, fault reaction, not ready).
// Quick stop active -> operation enabled uses transition 16 only when
// `use_transition_16`; otherwise it goes round via switch on disabled.
std::optional<Step> next_step(State from, State to, bool use_transition_16);

std::string_view to_string(State s);
std::string_view to_string(Command c);

}  // namespace advee::canopen::cia402
