// SPDX-License-Identifier: GPL-2.0
#include "advee/diagcenter/duration.hpp"

#include <gtest/gtest.h>

using advee::diagcenter::parse_duration;

TEST(Duration, UnitsAndBareSeconds) {
  EXPECT_EQ(parse_duration("30s"), 30.0);
  EXPECT_EQ(parse_duration("30"), 30.0);
  EXPECT_EQ(parse_duration("500ms"), 0.5);
  EXPECT_EQ(parse_duration("2m"), 120.0);
  EXPECT_EQ(parse_duration("1.5"), 1.5);
  EXPECT_EQ(parse_duration("1h"), 3600.0);
}

TEST(Duration, Rejected) {
  EXPECT_FALSE(parse_duration(""));
  EXPECT_FALSE(parse_duration("s"));
  EXPECT_FALSE(parse_duration("-1s"));
  EXPECT_FALSE(parse_duration("10 s"));
  EXPECT_FALSE(parse_duration("10x"));
  EXPECT_FALSE(parse_duration("inf"));
}
