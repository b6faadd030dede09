// SPDX-License-Identifier: GPL-2.0
// Error-frame decoding (linux/can/error.h) into the controller state. The
// socket itself is exercised on vcan by the VM tests (tests/vm/canopen).
#include "advee/canopen/socketcan.hpp"

#include <gtest/gtest.h>
#include <linux/can.h>
#include <linux/can/error.h>

namespace advee::canopen {
namespace {

can_frame error_frame(canid_t flags, std::uint8_t ctrl = 0) {
  can_frame f{};
  f.can_id = CAN_ERR_FLAG | flags;
  f.len = CAN_ERR_DLC;
  f.data[1] = ctrl;
  return f;
}

TEST(ErrorFrameTest, ControllerStatesFromTheCtrlByte) {
  EXPECT_EQ(decode_error_frame(error_frame(CAN_ERR_CRTL, CAN_ERR_CRTL_TX_WARNING)).state,
            CanControllerState::kErrorWarning);
  EXPECT_EQ(decode_error_frame(error_frame(CAN_ERR_CRTL, CAN_ERR_CRTL_RX_PASSIVE)).state,
            CanControllerState::kErrorPassive);
  EXPECT_EQ(decode_error_frame(error_frame(CAN_ERR_CRTL, CAN_ERR_CRTL_ACTIVE)).state,
            CanControllerState::kErrorActive);
  EXPECT_FALSE(decode_error_frame(error_frame(CAN_ERR_ACK)).state) << "no state change reported";
}

TEST(ErrorFrameTest, BusOffAndRestart) {
  EXPECT_EQ(decode_error_frame(error_frame(CAN_ERR_BUSOFF)).state, CanControllerState::kBusOff);
  const auto r = decode_error_frame(error_frame(CAN_ERR_RESTARTED));
  EXPECT_TRUE(r.restarted);
  EXPECT_EQ(r.state, CanControllerState::kErrorActive);
}

TEST(ErrorFrameTest, OverflowAndCounters) {
  can_frame f = error_frame(CAN_ERR_CRTL | CAN_ERR_CNT | CAN_ERR_ACK, CAN_ERR_CRTL_RX_OVERFLOW);
  f.data[6] = 96;
  f.data[7] = 3;
  const auto e = decode_error_frame(f);
  EXPECT_TRUE(e.rx_overflow);
  EXPECT_TRUE(e.no_ack);
  EXPECT_EQ(e.tx_errors, 96);
  EXPECT_EQ(e.rx_errors, 3);
}

TEST(CanSocketTest, UnknownInterfaceIsAnError) {
  EXPECT_THROW(CanSocket::open("nosuchcan0"), std::system_error);
}

}  // namespace
}  // namespace advee::canopen
