// SPDX-License-Identifier: GPL-2.0
// The bridge's odometry estimate and the history replayed to new pages.
#include <gtest/gtest.h>

#include <cmath>

#include "advee/web/history.hpp"
#include "advee/web/odometry.hpp"

namespace advee::web {
namespace {

TEST(Odometry, StraightLineFromTheStartPose) {
  OdometryIntegrator o({2.0, 2.0, M_PI / 2});
  for (int i = 0; i < 4; ++i) o.add(0.5, 0.0, 0.25);  // 0.5 m north
  EXPECT_NEAR(o.pose().x, 2.0, 1e-12);
  EXPECT_NEAR(o.pose().y, 2.5, 1e-12);
  EXPECT_NEAR(o.pose().heading, M_PI / 2, 1e-12);
}

TEST(Odometry, FullCircleCloses) {
  OdometryIntegrator o({1.0, 1.0, 0.0});
  const double v = 0.5, r = 1.7, w = v / r, period = 2 * M_PI / w;
  const int n = 400;
  for (int i = 0; i < n; ++i) o.add(v, w, period / n);
  EXPECT_NEAR(o.pose().x, 1.0, 1e-9);
  EXPECT_NEAR(o.pose().y, 1.0, 1e-9);
  EXPECT_NEAR(std::remainder(o.pose().heading, 2 * M_PI), 0.0, 1e-9);
}

TEST(Odometry, QuarterTurnLeftEndsAtTheArcEnd) {
  OdometryIntegrator o;
  const double r = 2.0, w = 0.25;
  o.add(r * w, w, (M_PI / 2) / w);  // one sample, exact arc
  EXPECT_NEAR(o.pose().x, r, 1e-12);
  EXPECT_NEAR(o.pose().y, r, 1e-12);
  EXPECT_NEAR(o.pose().heading, M_PI / 2, 1e-12);
}

TEST(Odometry, BadSamplesAreIgnored) {
  OdometryIntegrator o({1, 1, 0});
  o.add(NAN, 0, 0.25);
  o.add(1, 0, -1);
  o.add(1, 0, 0);
  EXPECT_EQ(o.pose().x, 1);
  const auto j = o.to_json(42);
  EXPECT_EQ(j["channel"], "WEB_ODO_POSE");
  EXPECT_EQ(j["utime"], 42);
  EXPECT_EQ(j["x_m"], 1.0);
}

TEST(History, DropsOlderThanTheWindow) {
  History h(10.0, 100);
  h.add(0.0, "a");
  h.add(5.0, "b");
  h.add(10.5, "c");
  ASSERT_EQ(h.size(), 2u);
  EXPECT_EQ(h.payloads().front(), "b");
  EXPECT_EQ(h.payloads().back(), "c");
}

TEST(History, BoundedInCount) {
  History h(1e9, 3);
  for (int i = 0; i < 10; ++i) h.add(i, std::to_string(i));
  ASSERT_EQ(h.size(), 3u);
  EXPECT_EQ(h.payloads().front(), "7");
}

TEST(History, KeepsWhatThePagePlots) {
  EXPECT_TRUE(kept_in_history("WEB_ODO_POSE"));
  EXPECT_TRUE(kept_in_history("SIM_DATA_POSE"));
  EXPECT_TRUE(kept_in_history("LL_DATA_TEMPERATURE"));
  EXPECT_TRUE(kept_in_history("LL_DATA_DRIVES"));
  EXPECT_FALSE(kept_in_history("CM_DATA_STATE"));
  EXPECT_FALSE(kept_in_history("LL_DATA_SRFS"));
}

}  // namespace
}  // namespace advee::web
