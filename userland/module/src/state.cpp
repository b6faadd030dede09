// SPDX-License-Identifier: GPL-2.0
#include "advee/module/state.hpp"

#include <array>
#include <cctype>
#include <string>

namespace advee::module {
namespace {

constexpr auto A = Transition::Allowed;
constexpr auto M = Transition::ManualOnly;
constexpr auto X = Transition::Refused;

// kTable[from][to], indices are the wire values. Rows:
//  INIT:  configuration loaded -> RUN or PAUSE (thesis: "either RUN or PAUSE").
//  RUN/PAUSE: superior modules switch between them; STOP by hand only.
//  STOP:  left by hand only (to RUN or PAUSE).
//  ERROR: recovery re-initialises or resumes.
//  TERMINATE: final. UNKNOWN is never a state a module is in or goes to.
//  Staying in the same state is not a transition.
constexpr std::array<std::array<Transition, 7>, 7> kTable{{
    //         UNK INIT STOP RUN ERR TERM PAUSE
    /* UNK  */ {X, X, X, X, X, X, X},
    /* INIT */ {X, X, X, A, A, A, A},
    /* STOP */ {X, X, X, M, A, A, M},
    /* RUN  */ {X, X, M, X, A, A, A},
    /* ERR  */ {X, A, X, A, X, A, A},
    /* TERM */ {X, X, X, X, X, X, X},
    /* PAUSE*/ {X, X, M, A, A, A, X},
}};

}  // namespace

Transition transition(State from, State to) {
  return kTable[static_cast<std::size_t>(from)][static_cast<std::size_t>(to)];
}

bool transition_allowed(State from, State to, bool manual) {
  switch (transition(from, to)) {
    case Transition::Allowed: return true;
    case Transition::ManualOnly: return manual;
    case Transition::Refused: return false;
  }
  return false;
}

std::string_view to_string(State s) {
  switch (s) {
    case State::Unknown: return "UNKNOWN";
    case State::Init: return "INIT";
    case State::Stop: return "STOP";
    case State::Run: return "RUN";
    case State::Error: return "ERROR";
    case State::Terminate: return "TERMINATE";
    case State::Pause: return "PAUSE";
  }
  return "UNKNOWN";
}

std::optional<State> parse_state(std::string_view s) {
  std::string up;
  for (char c : s) up += static_cast<char>(std::toupper(static_cast<unsigned char>(c)));
  for (State st : kAllStates)
    if (to_string(st) == up) return st;
  return std::nullopt;
}

std::optional<State> state_from_wire(std::int8_t v) {
  if (v < 0 || v > 6) return std::nullopt;
  return static_cast<State>(v);
}

}  // namespace advee::module
