// SPDX-License-Identifier: GPL-2.0
#include "advee/canopen/cia402.hpp"

namespace advee::canopen::cia402 {

State decode(std::uint16_t s) {
  // Masks from CiA 402 (canopen-notes.md §3.9): bit 5 only matters where it
  // separates quick stop active from operation enabled.
  if ((s & 0x4F) == 0x00) return State::kNotReadyToSwitchOn;
  if ((s & 0x4F) == 0x40) return State::kSwitchOnDisabled;
  if ((s & 0x6F) == 0x21) return State::kReadyToSwitchOn;
  if ((s & 0x6F) == 0x23) return State::kSwitchedOn;
  if ((s & 0x6F) == 0x27) return State::kOperationEnabled;
  if ((s & 0x6F) == 0x07) return State::kQuickStopActive;
  if ((s & 0x4F) == 0x0F) return State::kFaultReactionActive;
  if ((s & 0x4F) == 0x08) return State::kFault;
  // Combinations the standard does not define (e.g. 0x4F): treat as not ready,
  // which the path planner only waits on.
  return State::kNotReadyToSwitchOn;
}

std::uint16_t statusword_bits(State s) {
  switch (s) {
    case State::kNotReadyToSwitchOn: return 0x0000;
    case State::kSwitchOnDisabled: return 0x0040;
    case State::kReadyToSwitchOn: return 0x0031;
    case State::kSwitchedOn: return 0x0033;
    case State::kOperationEnabled: return 0x0037;
    case State::kQuickStopActive: return 0x0017;
    case State::kFaultReactionActive: return 0x001F;
    case State::kFault: return 0x0008;
  }
  return 0;
}

std::uint16_t apply(Command c, std::uint16_t w) {
  // Bits 7, 3, 2, 1, 0 per command; x = kept.
  constexpr std::uint16_t kLow4 = 0x000F;
  switch (c) {
    case Command::kShutdown: return static_cast<std::uint16_t>((w & ~(kLow4 | cw::kFaultReset)) | 0x0006);
    case Command::kSwitchOn: return static_cast<std::uint16_t>((w & ~(kLow4 | cw::kFaultReset)) | 0x0007);
    case Command::kEnableOperation: return static_cast<std::uint16_t>((w & ~(kLow4 | cw::kFaultReset)) | 0x000F);
    case Command::kDisableVoltage: return static_cast<std::uint16_t>(w & ~(kLow4 | cw::kFaultReset));
    case Command::kQuickStop: return static_cast<std::uint16_t>((w & ~(kLow4 | cw::kFaultReset)) | 0x0002);
    case Command::kDisableOperation: return static_cast<std::uint16_t>((w & ~(kLow4 | cw::kFaultReset)) | 0x0007);
    case Command::kFaultReset: return static_cast<std::uint16_t>(w | cw::kFaultReset);
  }
  return w;
}

std::optional<Command> command_in(std::uint16_t w, std::uint16_t previous, State s) {
  if (s == State::kFault) {
    if ((w & cw::kFaultReset) && !(previous & cw::kFaultReset)) return Command::kFaultReset;
    return std::nullopt;
  }
  if (w & cw::kFaultReset) return std::nullopt;  // bit 7 high outside fault: no command
  if (!(w & cw::kEnableVoltage)) return Command::kDisableVoltage;
  if (!(w & cw::kQuickStop)) return Command::kQuickStop;
  if (!(w & cw::kSwitchOn)) return Command::kShutdown;
  if (!(w & cw::kEnableOperation)) return s == State::kOperationEnabled ? Command::kDisableOperation : Command::kSwitchOn;
  return Command::kEnableOperation;
}

std::optional<Step> next_step(State from, State to, bool use16) {
  using S = State;
  using C = Command;
  if (from == to) return std::nullopt;
  switch (from) {
    case S::kNotReadyToSwitchOn:
    case S::kFaultReactionActive:
      return std::nullopt;  // the drive moves on by itself (transitions 1, 14)
    case S::kFault:
      return Step{C::kFaultReset, 15, S::kSwitchOnDisabled};
    default:
      break;
  }
  switch (to) {
    case S::kOperationEnabled:
      switch (from) {
        case S::kSwitchOnDisabled: return Step{C::kShutdown, 2, S::kReadyToSwitchOn};
        case S::kReadyToSwitchOn: return Step{C::kSwitchOn, 3, S::kSwitchedOn};
        case S::kSwitchedOn: return Step{C::kEnableOperation, 4, S::kOperationEnabled};
        case S::kQuickStopActive:
          if (use16) return Step{C::kEnableOperation, 16, S::kOperationEnabled};
          return Step{C::kDisableVoltage, 12, S::kSwitchOnDisabled};
        default: return std::nullopt;
      }
    case S::kSwitchedOn:
      switch (from) {
        case S::kSwitchOnDisabled: return Step{C::kShutdown, 2, S::kReadyToSwitchOn};
        case S::kReadyToSwitchOn: return Step{C::kSwitchOn, 3, S::kSwitchedOn};
        case S::kOperationEnabled: return Step{C::kDisableOperation, 5, S::kSwitchedOn};
        case S::kQuickStopActive: return Step{C::kDisableVoltage, 12, S::kSwitchOnDisabled};
        default: return std::nullopt;
      }
    case S::kReadyToSwitchOn:
      switch (from) {
        case S::kSwitchOnDisabled: return Step{C::kShutdown, 2, S::kReadyToSwitchOn};
        case S::kSwitchedOn: return Step{C::kShutdown, 6, S::kReadyToSwitchOn};
        case S::kOperationEnabled: return Step{C::kShutdown, 8, S::kReadyToSwitchOn};
        case S::kQuickStopActive: return Step{C::kDisableVoltage, 12, S::kSwitchOnDisabled};
        default: return std::nullopt;
      }
    case S::kSwitchOnDisabled:
      switch (from) {
        case S::kReadyToSwitchOn: return Step{C::kDisableVoltage, 7, S::kSwitchOnDisabled};
        case S::kOperationEnabled: return Step{C::kDisableVoltage, 9, S::kSwitchOnDisabled};
        case S::kSwitchedOn: return Step{C::kDisableVoltage, 10, S::kSwitchOnDisabled};
        case S::kQuickStopActive: return Step{C::kDisableVoltage, 12, S::kSwitchOnDisabled};
        default: return std::nullopt;
      }
    case S::kQuickStopActive:
      if (from == S::kOperationEnabled) return Step{C::kQuickStop, 11, S::kQuickStopActive};
      return std::nullopt;
    default:
      return std::nullopt;  // fault, fault reaction, not ready: not commandable
  }
}

std::string_view to_string(State s) {
  switch (s) {
    case State::kNotReadyToSwitchOn: return "not ready to switch on";
    case State::kSwitchOnDisabled: return "switch on disabled";
    case State::kReadyToSwitchOn: return "ready to switch on";
    case State::kSwitchedOn: return "switched on";
    case State::kOperationEnabled: return "operation enabled";
    case State::kQuickStopActive: return "quick stop active";
    case State::kFaultReactionActive: return "fault reaction active";
    case State::kFault: return "fault";
  }
  return "?";
}

std::string_view to_string(Command c) {
  switch (c) {
    case Command::kShutdown: return "shutdown";
    case Command::kSwitchOn: return "switch on";
    case Command::kEnableOperation: return "enable operation";
    case Command::kDisableVoltage: return "disable voltage";
    case Command::kQuickStop: return "quick stop";
    case Command::kDisableOperation: return "disable operation";
    case Command::kFaultReset: return "fault reset";
  }
  return "?";
}

}  // namespace advee::canopen::cia402
