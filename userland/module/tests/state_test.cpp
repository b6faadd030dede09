// SPDX-License-Identifier: GPL-2.0
// Every ordered pair of states against the edges of thesis figure 3.2 as
// read from its text, written out here edge by edge.
#include <gtest/gtest.h>

#include <set>
#include <string>

#include "advee/module/state.hpp"

using namespace advee::module;

namespace {

std::string edge(State a, State b) {
  return std::string(to_string(a)) + "->" + std::string(to_string(b));
}

const std::set<std::string> kAllowed = {
    "INIT->RUN",  "INIT->PAUSE", "INIT->ERROR",  "INIT->TERMINATE",
    "RUN->PAUSE", "RUN->ERROR",  "RUN->TERMINATE",
    "PAUSE->RUN", "PAUSE->ERROR", "PAUSE->TERMINATE",
    "STOP->ERROR", "STOP->TERMINATE",
    "ERROR->INIT", "ERROR->RUN", "ERROR->PAUSE", "ERROR->TERMINATE",
};
const std::set<std::string> kManualOnly = {
    "RUN->STOP", "PAUSE->STOP", "STOP->RUN", "STOP->PAUSE",
};

TEST(StateMachine, EveryPairMatchesTheDiagram) {
  int allowed = 0, manual = 0, refused = 0;
  for (State a : kAllStates) {
    for (State b : kAllStates) {
      const auto e = edge(a, b);
      if (kAllowed.count(e)) {
        EXPECT_EQ(transition(a, b), Transition::Allowed) << e;
        EXPECT_TRUE(transition_allowed(a, b, false)) << e;
        EXPECT_TRUE(transition_allowed(a, b, true)) << e;
        ++allowed;
      } else if (kManualOnly.count(e)) {
        EXPECT_EQ(transition(a, b), Transition::ManualOnly) << e;
        EXPECT_FALSE(transition_allowed(a, b, false)) << e;
        EXPECT_TRUE(transition_allowed(a, b, true)) << e;
        ++manual;
      } else {
        EXPECT_EQ(transition(a, b), Transition::Refused) << e;
        EXPECT_FALSE(transition_allowed(a, b, false)) << e;
        EXPECT_FALSE(transition_allowed(a, b, true)) << e;
        ++refused;
      }
    }
  }
  EXPECT_EQ(allowed, 16);
  EXPECT_EQ(manual, 4);
  EXPECT_EQ(refused, 49 - 20);
}

TEST(StateMachine, TerminateIsFinalAndReachableFromEveryLiveState) {
  for (State b : kAllStates) EXPECT_FALSE(transition_allowed(State::Terminate, b, true)) << edge(State::Terminate, b);
  for (State a : {State::Init, State::Run, State::Pause, State::Stop, State::Error})
    EXPECT_TRUE(transition_allowed(a, State::Terminate, false)) << edge(a, State::Terminate);
}

TEST(StateMachine, WireValuesAreThoseOfAdveeH) {
  EXPECT_EQ(static_cast<int>(State::Unknown), 0);
  EXPECT_EQ(static_cast<int>(State::Init), 1);
  EXPECT_EQ(static_cast<int>(State::Stop), 2);
  EXPECT_EQ(static_cast<int>(State::Run), 3);
  EXPECT_EQ(static_cast<int>(State::Error), 4);
  EXPECT_EQ(static_cast<int>(State::Terminate), 5);
  EXPECT_EQ(static_cast<int>(State::Pause), 6);
  EXPECT_FALSE(state_from_wire(7));
  EXPECT_FALSE(state_from_wire(-1));
  EXPECT_EQ(state_from_wire(6), State::Pause);
}

TEST(StateMachine, NamesParseBack) {
  for (State s : kAllStates) EXPECT_EQ(parse_state(to_string(s)), s);
  EXPECT_EQ(parse_state("pause"), State::Pause);
  EXPECT_FALSE(parse_state("running"));
}

}  // namespace
