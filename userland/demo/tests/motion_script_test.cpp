// SPDX-License-Identifier: GPL-2.0
#include "advee/demo/motion_script.hpp"

#include <gtest/gtest.h>

#include <cmath>

using advee::demo::MotionScript;
using advee::robotsim::parse_path;

namespace {

const char* kPath = R"(path:
  - {speed_mps: 0.5, steering_deg: 0, duration_s: 2}
  - {speed_mps: -0.3, steering_deg: 20, duration_s: 1.5}
)";

TEST(MotionScript, SegmentsInOrderThenEnd) {
  const MotionScript s(parse_path(kPath, "test.yaml"));
  EXPECT_DOUBLE_EQ(s.duration(), 3.5);
  auto c = s.at(0);
  ASSERT_TRUE(c);
  EXPECT_DOUBLE_EQ(c->speed_mps, 0.5);
  EXPECT_DOUBLE_EQ(c->steering_rad, 0);
  EXPECT_EQ(c->segment, 0u);
  c = s.at(1.999);
  ASSERT_TRUE(c);
  EXPECT_EQ(c->segment, 0u);
  c = s.at(2.0);
  ASSERT_TRUE(c);
  EXPECT_EQ(c->segment, 1u);
  EXPECT_DOUBLE_EQ(c->speed_mps, -0.3);
  EXPECT_NEAR(c->steering_rad, 20 * M_PI / 180, 1e-12);
  EXPECT_FALSE(s.at(3.5));
  EXPECT_FALSE(s.at(100));
  EXPECT_FALSE(s.at(-0.1));
}

TEST(MotionScript, TenHertzCommandsCoverThePath) {
  // At 10 Hz the planner sends 35 commands for 3.5 s: 20 of the first
  // segment, 15 of the second.
  const MotionScript s(parse_path(kPath, "test.yaml"));
  int n[2] = {0, 0};
  for (int i = 0;; ++i) {
    const auto c = s.at(i * 0.1 + 1e-9);
    if (!c) break;
    ++n[c->segment];
  }
  EXPECT_EQ(n[0], 20);
  EXPECT_EQ(n[1], 15);
}

TEST(MotionScript, BadFileNamesTheField) {
  try {
    parse_path("path:\n  - {speed_mps: 0.5, duration_s: 0}\n", "bad.yaml");
    FAIL() << "no error";
  } catch (const std::exception& e) {
    EXPECT_NE(std::string(e.what()).find("duration_s"), std::string::npos) << e.what();
  }
}

}  // namespace
