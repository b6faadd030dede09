// SPDX-License-Identifier: GPL-2.0
// CiA 402 statusword decoder, command table and path planner, and the axis
// state machine walking the simulated drive from every state.
#include "advee/canopen/cia402.hpp"

#include <gtest/gtest.h>

#include "advee/canopen/axis402.hpp"
#include "advee/canopen/sim/drive_sim.hpp"

namespace advee::canopen {
namespace {

using namespace std::chrono_literals;
using cia402::Command;
using cia402::State;

TEST(Cia402DecodeTest, StatuswordMasksOfTheStandard) {
  EXPECT_EQ(cia402::decode(0x0000), State::kNotReadyToSwitchOn);
  EXPECT_EQ(cia402::decode(0x0250), State::kSwitchOnDisabled);  // bits 4, 9 don't matter
  EXPECT_EQ(cia402::decode(0x0231), State::kReadyToSwitchOn);
  EXPECT_EQ(cia402::decode(0x0233), State::kSwitchedOn);
  EXPECT_EQ(cia402::decode(0x0637), State::kOperationEnabled);
  EXPECT_EQ(cia402::decode(0x0617), State::kQuickStopActive);
  EXPECT_EQ(cia402::decode(0x001F), State::kFaultReactionActive);
  EXPECT_EQ(cia402::decode(0x0208), State::kFault);
  EXPECT_EQ(cia402::decode(0x0228), State::kFault) << "bit 5 is not part of the fault mask";
}

TEST(Cia402DecodeTest, EveryStateSurvivesItsOwnStatusword) {
  for (State s : {State::kNotReadyToSwitchOn, State::kSwitchOnDisabled, State::kReadyToSwitchOn, State::kSwitchedOn,
                  State::kOperationEnabled, State::kQuickStopActive, State::kFaultReactionActive, State::kFault})
    EXPECT_EQ(cia402::decode(cia402::statusword_bits(s)), s) << cia402::to_string(s);
}

TEST(Cia402CommandTest, TypicalWordsAndKeptModeBits) {
  EXPECT_EQ(cia402::apply(Command::kShutdown, 0), 0x0006);
  EXPECT_EQ(cia402::apply(Command::kSwitchOn, 0x0006), 0x0007);
  EXPECT_EQ(cia402::apply(Command::kEnableOperation, 0x0007), 0x000F);
  EXPECT_EQ(cia402::apply(Command::kDisableVoltage, 0x000F), 0x0000);
  EXPECT_EQ(cia402::apply(Command::kQuickStop, 0x000F), 0x0002);
  EXPECT_EQ(cia402::apply(Command::kDisableOperation, 0x000F), 0x0007);
  EXPECT_EQ(cia402::apply(Command::kFaultReset, 0x0000), 0x0080);
  EXPECT_EQ(cia402::apply(Command::kShutdown, 0x0080), 0x0006) << "the next command drops the reset bit";
  EXPECT_EQ(cia402::apply(Command::kEnableOperation, 0x0170), 0x017F) << "halt and pp bits are kept";
}

TEST(Cia402CommandTest, DriveSideDecodingOfTheCommandTable) {
  EXPECT_EQ(cia402::command_in(0x0006, 0, State::kSwitchOnDisabled), Command::kShutdown);
  EXPECT_EQ(cia402::command_in(0x0007, 0, State::kReadyToSwitchOn), Command::kSwitchOn);
  EXPECT_EQ(cia402::command_in(0x0007, 0, State::kOperationEnabled), Command::kDisableOperation);
  EXPECT_EQ(cia402::command_in(0x000B, 0, State::kOperationEnabled), Command::kQuickStop);
  EXPECT_EQ(cia402::command_in(0x000D, 0, State::kOperationEnabled), Command::kDisableVoltage);
  EXPECT_EQ(cia402::command_in(0x0080, 0x0000, State::kFault), Command::kFaultReset);
  EXPECT_EQ(cia402::command_in(0x0080, 0x0080, State::kFault), std::nullopt) << "no edge, no reset";
}

TEST(Cia402PathTest, EnableNeverJumpsAState) {
  std::vector<int> transitions;
  State s = State::kFault;
  while (auto step = cia402::next_step(s, State::kOperationEnabled, false)) {
    transitions.push_back(step->transition);
    s = step->expect;
  }
  EXPECT_EQ(s, State::kOperationEnabled);
  EXPECT_EQ(transitions, (std::vector<int>{15, 2, 3, 4}));
}

TEST(Cia402PathTest, QuickStopToEnabledUsesSixteenOnlyWhenAllowed) {
  EXPECT_EQ(cia402::next_step(State::kQuickStopActive, State::kOperationEnabled, true)->transition, 16);
  EXPECT_EQ(cia402::next_step(State::kQuickStopActive, State::kOperationEnabled, false)->transition, 12);
}

TEST(Cia402PathTest, UncommandableTargetsAndSelfMovingStates) {
  EXPECT_FALSE(cia402::next_step(State::kSwitchedOn, State::kFault, false));
  EXPECT_FALSE(cia402::next_step(State::kNotReadyToSwitchOn, State::kOperationEnabled, false));
  EXPECT_FALSE(cia402::next_step(State::kFaultReactionActive, State::kSwitchOnDisabled, false));
  EXPECT_FALSE(cia402::next_step(State::kSwitchedOn, State::kQuickStopActive, false));
  EXPECT_EQ(cia402::next_step(State::kOperationEnabled, State::kQuickStopActive, false)->transition, 11);
  EXPECT_EQ(cia402::next_step(State::kOperationEnabled, State::kSwitchOnDisabled, false)->transition, 9);
  EXPECT_EQ(cia402::next_step(State::kOperationEnabled, State::kReadyToSwitchOn, false)->transition, 8);
  EXPECT_EQ(cia402::next_step(State::kSwitchedOn, State::kSwitchOnDisabled, false)->transition, 10);
}

// Axis402 against the simulated drive's state machine, controlword by SDO-free
// direct writes (the drive sees exactly the words the axis sends).
class AxisTest : public testing::Test {
 protected:
  ManualClock clock;
  std::vector<CanFrame> drive_out;
  sim::SimulatedDrive drive{sim::DriveSimConfig{1, sim::DriveProfile::kIcla}, [this](const CanFrame& f) { drive_out.push_back(f); },
                            clock.fn()};
  std::vector<std::uint16_t> words;
  AxisConfig cfg{200ms, false};
  std::unique_ptr<Axis402> axis;
  std::optional<std::error_code> result;

  void SetUp() override { drive.power_on(); make_axis(); }
  void make_axis() {
    axis = std::make_unique<Axis402>(cfg, clock.fn(), [this](std::uint16_t w) {
      words.push_back(w);
      drive.od().write(0x6040, 0, to_bytes<std::uint16_t>(w));
    });
    axis->on_statusword(drive.od().get<std::uint16_t>(0x6041));
  }
  // Runs until the request completes; the statusword reaches the axis 1 ms
  // after each change, like a TPDO would.
  void run(State target) {
    result.reset();
    words.clear();
    axis->request(target, [this](std::error_code ec) { result = ec; });
    for (int i = 0; i < 5000 && !result; ++i) {
      clock.advance(1ms);
      drive.poll();
      axis->on_statusword(drive.od().get<std::uint16_t>(0x6041));
      axis->poll();
    }
  }
  void bring_to(State s) {
    if (s == State::kFault) {
      drive.inject_fault(0x5113);
      for (int i = 0; i < 10; ++i) { clock.advance(1ms); drive.poll(); }
      axis->on_statusword(drive.od().get<std::uint16_t>(0x6041));
      return;
    }
    if (s == State::kQuickStopActive) {
      run(State::kOperationEnabled);
      run(State::kQuickStopActive);
    } else {
      run(s);
    }
    ASSERT_EQ(drive.state(), s);
  }
};

TEST_F(AxisTest, EnableFromSwitchOnDisabledSendsShutdownSwitchOnEnable) {
  run(State::kOperationEnabled);
  ASSERT_TRUE(result);
  EXPECT_FALSE(*result) << result->message();
  EXPECT_EQ(drive.state(), State::kOperationEnabled);
  EXPECT_EQ(words, (std::vector<std::uint16_t>{0x0006, 0x0007, 0x000F}));
}

TEST_F(AxisTest, EveryCommandableStateReachesEveryOther) {
  const State all[] = {State::kSwitchOnDisabled, State::kReadyToSwitchOn, State::kSwitchedOn,
                       State::kOperationEnabled, State::kQuickStopActive, State::kFault};
  const State targets[] = {State::kSwitchOnDisabled, State::kReadyToSwitchOn, State::kSwitchedOn,
                           State::kOperationEnabled, State::kQuickStopActive};
  for (State from : all) {
    for (State to : targets) {
      SCOPED_TRACE(std::string(cia402::to_string(from)) + " -> " + std::string(cia402::to_string(to)));
      bring_to(from);
      run(to);
      ASSERT_TRUE(result);
      if (to == State::kQuickStopActive && from != State::kOperationEnabled) {
        EXPECT_FALSE(*result);
        EXPECT_EQ(drive.state(), from == State::kQuickStopActive ? State::kQuickStopActive : State::kSwitchOnDisabled);
      } else {
        EXPECT_FALSE(*result) << result->message();
        EXPECT_EQ(drive.state(), to);
      }
    }
  }
}

TEST_F(AxisTest, FaultResetIsARisingEdgeAndEnablesAfterwards) {
  run(State::kOperationEnabled);
  bring_to(State::kFault);
  EXPECT_EQ(axis->state(), State::kFault);
  run(State::kOperationEnabled);
  ASSERT_TRUE(result);
  EXPECT_FALSE(*result);
  EXPECT_EQ(words, (std::vector<std::uint16_t>{0x008F, 0x0006, 0x0007, 0x000F}));
}

TEST_F(AxisTest, PersistentFaultGivesUpAfterTwoEdges) {
  bring_to(State::kFault);
  // The controlwords go nowhere: a drive whose fault cause is still there.
  axis = std::make_unique<Axis402>(cfg, clock.fn(), [this](std::uint16_t w) { words.push_back(w); });
  axis->on_statusword(drive.od().get<std::uint16_t>(0x6041));
  run(State::kOperationEnabled);
  ASSERT_TRUE(result);
  EXPECT_EQ(*result, make_error_code(AxisError::kFault));
  EXPECT_EQ(words, (std::vector<std::uint16_t>{0x0080, 0x0000, 0x0080}));
}

TEST_F(AxisTest, RefusedTransition16FallsBackViaSwitchOnDisabled) {
  cfg.try_transition_16 = true;
  make_axis();
  drive.faults().refuse_transition_16 = true;
  bring_to(State::kQuickStopActive);
  run(State::kOperationEnabled);
  ASSERT_TRUE(result);
  EXPECT_FALSE(*result) << result->message();
  EXPECT_EQ(drive.state(), State::kOperationEnabled);
  // 0x000F (16, refused, times out), then 12, 2, 3, 4.
  EXPECT_EQ(words, (std::vector<std::uint16_t>{0x000F, 0x0000, 0x0006, 0x0007, 0x000F}));
  EXPECT_FALSE(axis->transition_16_usable());
}

TEST_F(AxisTest, Transition16IsUsedWhenTheDriveHasIt) {
  cfg.try_transition_16 = true;
  make_axis();
  bring_to(State::kQuickStopActive);
  run(State::kOperationEnabled);
  ASSERT_TRUE(result);
  EXPECT_FALSE(*result);
  EXPECT_EQ(words, (std::vector<std::uint16_t>{0x000F}));
}

TEST_F(AxisTest, WithoutTransition16ConfiguredItIsNeverTried) {
  bring_to(State::kQuickStopActive);
  run(State::kOperationEnabled);
  EXPECT_EQ(words, (std::vector<std::uint16_t>{0x0000, 0x0006, 0x0007, 0x000F}));
}

TEST_F(AxisTest, DriveThatDoesNotRespondTimesOutPerAxis) {
  axis = std::make_unique<Axis402>(cfg, clock.fn(), [this](std::uint16_t w) { words.push_back(w); });
  axis->on_statusword(0x0250);
  run(State::kOperationEnabled);
  ASSERT_TRUE(result);
  EXPECT_EQ(*result, make_error_code(AxisError::kTransitionTimeout));
  EXPECT_EQ(words, std::vector<std::uint16_t>{0x0006});
}

TEST_F(AxisTest, NoStatuswordAtAllTimesOutInsteadOfWaitingForever) {
  axis = std::make_unique<Axis402>(cfg, clock.fn(), [this](std::uint16_t w) { words.push_back(w); });
  axis->request(State::kOperationEnabled, [this](std::error_code ec) { result = ec; });
  clock.advance(199ms);
  axis->poll();
  EXPECT_FALSE(result);
  clock.advance(1ms);
  axis->poll();
  ASSERT_TRUE(result);
  EXPECT_EQ(*result, make_error_code(AxisError::kTransitionTimeout));
  EXPECT_TRUE(words.empty()) << "nothing is commanded blind";
}

TEST_F(AxisTest, NewRequestCancelsThePreviousOne) {
  std::optional<std::error_code> first;
  axis = std::make_unique<Axis402>(cfg, clock.fn(), [](std::uint16_t) {});
  axis->on_statusword(0x0250);
  axis->request(State::kOperationEnabled, [&](std::error_code ec) { first = ec; });
  axis->request(State::kSwitchOnDisabled, [](std::error_code) {});
  ASSERT_TRUE(first);
  EXPECT_EQ(*first, make_error_code(AxisError::kCancelled));
}

}  // namespace
}  // namespace advee::canopen
