// SPDX-License-Identifier: GPL-2.0
#include <gtest/gtest.h>

#include "advee/module/exit_code.hpp"

using namespace advee::module;

TEST(ExitCode, KindPlusDetail) {
  EXPECT_EQ(exit_code(ExitKind::Success), 0);
  EXPECT_EQ(exit_code(ExitKind::Resource, 1), 0x11);
  EXPECT_EQ(exit_code(ExitKind::Device, 15), 0x2f);
  EXPECT_EQ(exit_code(ExitKind::Other), 0x40);
}

TEST(ExitCode, DetailsThatWouldAliasAnotherKindAreRefused) {
  EXPECT_THROW(exit_code(ExitKind::Resource, 16), std::invalid_argument);  // would be 0x20
  EXPECT_THROW(exit_code(ExitKind::Device, -1), std::invalid_argument);
  EXPECT_THROW(exit_code(ExitKind::Success, 1), std::invalid_argument);
}

TEST(ExitCode, EveryCodeDecodesBackToItsKind) {
  for (ExitKind k : {ExitKind::Resource, ExitKind::Device, ExitKind::Other}) {
    for (int d = 0; d <= kMaxExitDetail; ++d) {
      const auto dec = decode_exit_code(exit_code(k, d));
      ASSERT_TRUE(dec);
      EXPECT_EQ(dec->kind, k);
      EXPECT_EQ(dec->detail, d);
    }
  }
  EXPECT_FALSE(decode_exit_code(1));
  EXPECT_FALSE(decode_exit_code(0x30));
  EXPECT_FALSE(decode_exit_code(137));
}

TEST(ExitCode, Descriptions) {
  EXPECT_EQ(describe_exit_code(0x23), "device error 3");
  EXPECT_EQ(describe_exit_code(0x10), "resource error");
  EXPECT_EQ(describe_exit_code(137), "killed by SIGKILL");
  EXPECT_EQ(describe_exit_code(143), "killed by SIGTERM");
  EXPECT_EQ(describe_exit_code(3), "exit code 3 (outside the module convention)");
}

TEST(ExitCode, ModuleExitCarriesTheCode) {
  ModuleExit e(ExitKind::Device, 2, "no device");
  EXPECT_EQ(e.code(), 0x22);
  EXPECT_STREQ(e.what(), "no device");
}
