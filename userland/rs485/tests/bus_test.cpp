// SPDX-License-Identifier: GPL-2.0
// Bus without the kernel module (the host cannot load it): device names and
// the errors a user sees when the device is wrong. The real stack is tested
// in the VM (tests/vm/rs485/).
#include "advee/rs485/bus.hpp"

#include <fcntl.h>
#include <gtest/gtest.h>
#include <stdlib.h>
#include <unistd.h>

namespace advee::rs485 {
namespace {

TEST(Rs485Bus, BusNamesResolveUnderDevRs485) {
  EXPECT_EQ(Bus::resolve_device("a"), "/dev/rs485/a");
  EXPECT_EQ(Bus::resolve_device("power"), "/dev/rs485/power");
  EXPECT_EQ(Bus::resolve_device("/dev/ttyTSU0"), "/dev/ttyTSU0");
  EXPECT_EQ(Bus::resolve_device("./tty"), "./tty");
}

TEST(Rs485Bus, MissingDeviceThrowsWithItsName) {
  try {
    Bus bus("/dev/rs485-test-does-not-exist");
    FAIL() << "opened a missing device";
  } catch (const std::system_error& e) {
    EXPECT_EQ(e.code(), std::errc::no_such_file_or_directory);
    EXPECT_NE(std::string(e.what()).find("/dev/rs485-test-does-not-exist"), std::string::npos);
  }
}

TEST(Rs485Bus, NotATtyThrowsNotATty) {
  try {
    Bus bus("/dev/null");
    FAIL() << "accepted /dev/null";
  } catch (const std::system_error& e) {
    EXPECT_EQ(e.code(), std::errc::inappropriate_io_control_operation);
  }
}

TEST(Rs485Bus, UnknownDisciplineNumberFailsTheAttach) {
  // A pty with a discipline number no kernel registers (N_* ends at 30).
  int master = ::posix_openpt(O_RDWR | O_NOCTTY);
  ASSERT_GE(master, 0);
  ASSERT_EQ(::grantpt(master), 0);
  ASSERT_EQ(::unlockpt(master), 0);
  const std::string slave = ::ptsname(master);
  BusOptions o;
  o.ldisc = 200;
  EXPECT_THROW(Bus(slave, o), std::system_error);
  ::close(master);
}

TEST(Rs485Bus, DefaultDisciplineIsTheModulesOr29) {
  const int ld = Bus::default_ldisc();
  if (::access("/sys/module/n_rs485/parameters/ldisc", R_OK) != 0) {
    EXPECT_EQ(ld, 29);
  }
  EXPECT_GT(ld, 0);
}

}  // namespace
}  // namespace advee::rs485
