// SPDX-License-Identifier: GPL-2.0
// /scene.json from advee-robot-sim's own example files.
#include "advee/web/scene.hpp"

#include <gtest/gtest.h>

namespace advee::web {
namespace {

const std::string kConf = ADVEE_ROBOTSIM_CONF_DIR;

TEST(Scene, ExampleRobotAndRoom) {
  const auto s = load_scene(kConf + "/robot.yaml", kConf + "/room.yaml");
  ASSERT_FALSE(s.contains("errors")) << s.dump();
  const auto& r = s["robot"];
  EXPECT_DOUBLE_EQ(r["outline"]["front_m"].get<double>(), 0.90);
  EXPECT_DOUBLE_EQ(r["outline"]["rear_m"].get<double>(), 0.25);
  EXPECT_DOUBLE_EQ(r["outline"]["half_width_m"].get<double>(), 0.30);
  ASSERT_EQ(r["srfs"].size(), 16u);
  // Ids as driver_rs485a.yaml: front board 0..7, rear board 8..15.
  std::vector<int> ids;
  for (const auto& srf : r["srfs"]) ids.push_back(srf["id"].get<int>());
  std::sort(ids.begin(), ids.end());
  for (int i = 0; i < 16; ++i) EXPECT_EQ(ids[static_cast<std::size_t>(i)], i);
  // front index 0: (0.80, 0.25) at 60 degrees
  for (const auto& srf : r["srfs"])
    if (srf["id"] == 0) {
      EXPECT_DOUBLE_EQ(srf["x"].get<double>(), 0.80);
      EXPECT_DOUBLE_EQ(srf["y"].get<double>(), 0.25);
      EXPECT_NEAR(srf["heading_rad"].get<double>(), 1.0471975512, 1e-9);
    }
  EXPECT_DOUBLE_EQ(r["start"]["x"].get<double>(), 2.0);
  const auto& w = s["world"];
  EXPECT_GE(w["segments"].size(), 4u);
  EXPECT_GE(w["beacons"].size(), 1u);
}

TEST(Scene, BrokenFileIsReportedAndTheRestKept) {
  const auto s = load_scene("/nonexistent/robot.yaml", kConf + "/room.yaml");
  ASSERT_TRUE(s.contains("errors"));
  EXPECT_EQ(s["errors"].size(), 1u);
  EXPECT_NE(s["errors"][0].get<std::string>().find("/nonexistent/robot.yaml"), std::string::npos);
  EXPECT_FALSE(s.contains("robot"));
  EXPECT_TRUE(s.contains("world"));
}

TEST(Scene, NoFilesNoScene) {
  const auto s = load_scene("", "");
  EXPECT_TRUE(s.empty());
}

}  // namespace
}  // namespace advee::web
