// SPDX-License-Identifier: GPL-2.0
// Control commands as a world model or a test sends them.
#include <gtest/gtest.h>

#include "advee/rs485sim/control.hpp"
#include "advee/rs485sim/devices.hpp"
#include "test_util.hpp"

namespace advee::rs485sim {
namespace {

using test::bytes;
using test::kT0;

class ControlTest : public ::testing::Test {
 protected:
  ControlTest() : a("a", false), power("power", true), ctl({&a, &power}) {
    a.add(std::make_unique<Sd1>(0x10));
    a.add(std::make_unique<So1>(0x20));
    power.add(std::make_unique<Psc1>(0x01));
    power.add(std::make_unique<Sd1>(0x10));
  }
  std::vector<std::uint8_t> ask(BusSim& bus, std::uint8_t addr, std::uint8_t instr) {
    const auto r = test::transact(bus, Frame{addr, instr, 0, {}});
    EXPECT_EQ(r.size(), 1u);
    return r.empty() ? std::vector<std::uint8_t>{} : r[0].frame.data;
  }
  BusSim a, power;
  Control ctl;
};

TEST_F(ControlTest, SetReadingChangesTheAnswer) {
  EXPECT_EQ(ctl.execute("set a:sd1@0x10 srf 3 1.25", kT0), "ok");
  EXPECT_EQ(ctl.execute("set a:sd1@16 ir all 0.2", kT0), "ok");
  const auto d = ask(a, 0x10, Sd1::kGetBoth);
  ASSERT_EQ(d.size(), 20u);
  EXPECT_EQ(d[7] | d[8] << 8, 125);
  EXPECT_EQ(d[18], 100);
  EXPECT_EQ(d[19], 100);
}

TEST_F(ControlTest, AmbiguousDeviceNeedsTheBus) {
  const auto r = ctl.execute("set sd1@0x10 srf 0 1", kT0);
  EXPECT_EQ(r.rfind("error:", 0), 0u) << r;
  EXPECT_NE(r.find("several buses"), std::string::npos) << r;
  EXPECT_EQ(ctl.execute("set so1@0x20 ticks 7 -7", kT0), "ok");
}

TEST_F(ControlTest, ErrorsSayWhatIsWrong) {
  EXPECT_NE(ctl.execute("set so1@0x21 ticks 1 1", kT0).find("no device so1@0x21"), std::string::npos);
  EXPECT_NE(ctl.execute("set a:sd1@0x10 srf 9 1", kT0).find("out of range"), std::string::npos);
  EXPECT_NE(ctl.execute("set a:sd1@0x10 srf 1 far", kT0).find("not a number"), std::string::npos);
  EXPECT_NE(ctl.execute("frobnicate", kT0).find("unknown command"), std::string::npos);
  EXPECT_NE(ctl.execute("event a:sd1@0x10 power", kT0).find("only psc1"), std::string::npos);
  EXPECT_NE(ctl.execute("fault so1@0x20 explode once", kT0).find("fault kind"), std::string::npos);
}

TEST_F(ControlTest, EventCommandSendsAFrame) {
  EXPECT_EQ(ctl.execute("event psc1@0x01 pause 1 0x03", kT0), "ok");
  const auto tx = power.take_due(Clock::now() + std::chrono::hours(1));
  ASSERT_EQ(tx.size(), 1u);
  EXPECT_EQ(test::decode(tx[0].words)->frame, (Frame{0x01, Psc1::kPauseEvent, kRespEvent, bytes({1, 3})}));
}

TEST_F(ControlTest, FaultOnceAndStats) {
  EXPECT_EQ(ctl.execute("fault so1@0x20 bad-crc once", kT0), "ok");
  auto r = test::transact(a, Frame{0x20, So1::kResetTicks, 0, {}});
  ASSERT_EQ(r.size(), 1u);
  EXPECT_FALSE(r[0].crc_ok);
  r = test::transact(a, Frame{0x20, So1::kResetTicks, kReqResend, {}});
  ASSERT_EQ(r.size(), 1u);
  EXPECT_TRUE(r[0].crc_ok);
  const auto s = ctl.execute("stats so1@0x20", kT0);
  EXPECT_NE(s.find("resends=1"), std::string::npos) << s;
  EXPECT_NE(s.find("corrupted=1"), std::string::npos) << s;
  EXPECT_NE(s.find("exec[0x02]=1"), std::string::npos) << s;
  EXPECT_EQ(ctl.execute("reset-stats so1@0x20", kT0), "ok");
  EXPECT_NE(ctl.execute("stats so1@0x20", kT0).find("requests=0"), std::string::npos);
}

TEST_F(ControlTest, ListNamesEveryDevice) {
  EXPECT_EQ(ctl.execute("list", kT0), "ok\na:sd1@0x10\na:so1@0x20\npower:psc1@0x01\npower:sd1@0x10");
}

}  // namespace
}  // namespace advee::rs485sim
