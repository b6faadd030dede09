// SPDX-License-Identifier: GPL-2.0
// Controller state changes become error reports (bus-off on the error
// channel, not only on stderr).
#include "advee/driver_canbus/bus_state.hpp"

#include <gtest/gtest.h>

namespace advee::driver_canbus {
namespace {

using canopen::CanControllerState;
using canopen::CanErrorInfo;

CanErrorInfo state(CanControllerState s) {
  CanErrorInfo e;
  e.state = s;
  return e;
}

TEST(BusStateTest, BusOffIsAnErrorReportedOncePerEpisode) {
  BusStateReporter r("can0");
  auto off = r.on_error(state(CanControllerState::kBusOff));
  ASSERT_TRUE(off);
  EXPECT_EQ(off->severity, module::Severity::Error);
  EXPECT_EQ(off->text, "CAN controller can0: bus-off, transmission held until the controller restarts");
  EXPECT_FALSE(r.on_error(state(CanControllerState::kBusOff)));
  EXPECT_FALSE(r.on_error(CanErrorInfo{})) << "an error frame without a state change";
  CanErrorInfo restarted;
  restarted.restarted = true;
  restarted.state = CanControllerState::kErrorActive;
  auto back = r.on_error(restarted);
  ASSERT_TRUE(back);
  EXPECT_EQ(back->severity, module::Severity::Notice);
  EXPECT_EQ(back->text, "CAN controller can0: error-active again (was bus-off)");
  ASSERT_TRUE(r.on_error(state(CanControllerState::kBusOff)));
}

TEST(BusStateTest, PassiveAndWarningAreWarnings) {
  BusStateReporter r("vcan0");
  EXPECT_FALSE(r.on_error(state(CanControllerState::kErrorActive))) << "starts error-active";
  auto w = r.on_error(state(CanControllerState::kErrorWarning));
  ASSERT_TRUE(w);
  EXPECT_EQ(w->severity, module::Severity::Warning);
  auto p = r.on_error(state(CanControllerState::kErrorPassive));
  ASSERT_TRUE(p);
  EXPECT_EQ(p->text, "CAN controller vcan0: error-passive");
}

using Changes = std::vector<std::pair<std::uint16_t, bool>>;

TEST(BusStateTest, TheMasterReportsPassiveAndBusOffAsItsOwnEmcy) {
  BusStateReporter r("can0");
  EXPECT_EQ(r.on_error(state(CanControllerState::kErrorWarning))->emcy, Changes{}) << "warning is no EMCY error";
  EXPECT_EQ(r.on_error(state(CanControllerState::kErrorPassive))->emcy, (Changes{{0x8120, true}}));
  EXPECT_EQ(r.on_error(state(CanControllerState::kBusOff))->emcy, (Changes{{0x8140, true}, {0x8120, false}}))
      << "raised before cleared: the reset's register still shows the bus-off";
  EXPECT_EQ(r.on_error(state(CanControllerState::kErrorActive))->emcy, (Changes{{0x8140, false}}));
  EXPECT_EQ(r.on_error(state(CanControllerState::kBusOff))->emcy, (Changes{{0x8140, true}}));
  EXPECT_EQ(r.on_error(state(CanControllerState::kErrorPassive))->emcy,
            (Changes{{0x8120, true}, {0x8140, false}}));
}

}  // namespace
}  // namespace advee::driver_canbus
