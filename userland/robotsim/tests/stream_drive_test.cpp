// SPDX-License-Identifier: GPL-2.0
#include <gtest/gtest.h>
#include <unistd.h>

#include <cstring>

#include "advee/robotsim/stream_drive.hpp"

namespace advee::robotsim {
namespace {

struct Pipe {
  UniqueFd read_end, write_end;
  Pipe() {
    int fds[2];
    if (pipe(fds) != 0) throw std::runtime_error("pipe");
    read_end.reset(fds[0]);
    write_end.reset(fds[1]);
  }
  void write(const char* s) const { ASSERT_EQ(::write(write_end.get(), s, std::strlen(s)), ssize_t(std::strlen(s))); }
};

TEST(StreamDrive, LatestCompleteLineHoldsWithoutBlocking) {
  Pipe p;
  StreamDrive drive(std::move(p.read_end));
  EXPECT_EQ(drive.command(0).speed_mps, 0);  // nothing yet: stand still, no blocking
  p.write("0.5 10\n# comment\n\n-0.2 -5\n0.3");
  DriveCommand c = drive.command(0);
  EXPECT_DOUBLE_EQ(c.speed_mps, -0.2);
  EXPECT_NEAR(c.steering_rad, deg_to_rad(-5), 1e-15);
  p.write(" 20\n");  // completes the partial line
  c = drive.command(0);
  EXPECT_DOUBLE_EQ(c.speed_mps, 0.3);
  EXPECT_NEAR(c.steering_rad, deg_to_rad(20), 1e-15);
  p.write_end.reset();
  EXPECT_DOUBLE_EQ(drive.command(0).speed_mps, 0.3);  // end of input keeps the last command
  EXPECT_TRUE(drive.at_eof());
}

TEST(StreamDrive, BadLineIsNamed) {
  Pipe p;
  StreamDrive drive(std::move(p.read_end));
  p.write("fast left\n");
  try {
    drive.command(0);
    FAIL() << "accepted 'fast left'";
  } catch (const ConfigError& e) {
    EXPECT_STREQ(e.what(), "drive input: 'fast left': expected SPEED_MPS STEERING_DEG");
  }
  EXPECT_THROW(parse_drive_line("0.5 10 3"), ConfigError);
}

}  // namespace
}  // namespace advee::robotsim
