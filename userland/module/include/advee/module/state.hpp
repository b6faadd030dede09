// SPDX-License-Identifier: GPL-2.0
// The state machine every module follows (thesis 3.3, figure 3.2). Values are
// those of advee.h and of common.data_state_t on the wire.
#pragma once

#include <cstdint>
#include <optional>
#include <string_view>

namespace advee::module {

enum class State : std::int8_t {
  Unknown = 0,
  Init = 1,
  Stop = 2,
  Run = 3,
  Error = 4,
  Terminate = 5,
  Pause = 6,
};

inline constexpr State kAllStates[] = {State::Unknown, State::Init,      State::Stop, State::Run,
                                       State::Error,   State::Terminate, State::Pause};

enum class Transition {
  Allowed,         // any sender may ask for it
  ManualOnly,      // only an operator's command (cmd_state_t.manual): entering or leaving STOP
  Refused,         // not an edge of the diagram (including staying in the same state)
};

// The edge from -> to of the diagram.
Transition transition(State from, State to);
// Whether a request from a module (manual = false) or an operator
// (manual = true) may move the state machine from -> to.
bool transition_allowed(State from, State to, bool manual);

std::string_view to_string(State s);                  // "RUN", ...
std::optional<State> parse_state(std::string_view s);  // case-insensitive; "run" -> Run
std::optional<State> state_from_wire(std::int8_t v);   // nullopt for values outside the enum

}  // namespace advee::module
