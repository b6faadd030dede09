// SPDX-License-Identifier: GPL-2.0
// Which LCM URL a program uses (advee/msgs/bus.hpp): its own setting, else
// LCM_DEFAULT_URL, else the robot's /etc/advee/lcm.conf, else LCM's default.
#include <gtest/gtest.h>
#include <unistd.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <optional>
#include <string>

#include "advee/msgs/bus.hpp"

namespace {

using advee::msgs::bus_url;
using advee::msgs::url_in_conf_file;

class BusUrlTest : public ::testing::Test {
 protected:
  void SetUp() override {
    if (const char* e = std::getenv("LCM_DEFAULT_URL")) saved_ = e;
    unsetenv("LCM_DEFAULT_URL");
    conf_ = std::filesystem::temp_directory_path() / ("advee-lcm-" + std::to_string(getpid()) + ".conf");
  }
  void TearDown() override {
    std::filesystem::remove(conf_);
    if (saved_) setenv("LCM_DEFAULT_URL", saved_->c_str(), 1);
  }
  void write(const std::string& text) { std::ofstream(conf_) << text; }
  std::optional<std::string> saved_;
  std::filesystem::path conf_;
};

// Each source in turn added in front of the ones before: the newest wins.
TEST_F(BusUrlTest, FirstFoundWins) {
  write("# robot\nLCM_DEFAULT_URL=udpm://239.255.76.67:7667?ttl=1\n");
  auto u = bus_url("", "--lcm", conf_.string());
  EXPECT_EQ(u.url, "udpm://239.255.76.67:7667?ttl=1");
  EXPECT_EQ(u.from, conf_.string());

  setenv("LCM_DEFAULT_URL", "udpm://239.255.76.67:7700?ttl=0", 1);
  u = bus_url("", "--lcm", conf_.string());
  EXPECT_EQ(u.url, "udpm://239.255.76.67:7700?ttl=0");
  EXPECT_EQ(u.from, "LCM_DEFAULT_URL");

  u = bus_url("memq://", "module.lcm_url", conf_.string());
  EXPECT_EQ(u.url, "memq://");
  EXPECT_EQ(u.from, "module.lcm_url");
}

TEST_F(BusUrlTest, LcmsDefaultWithoutFile) {
  const auto u = bus_url("", "--lcm", conf_.string());
  EXPECT_EQ(u.url, advee::msgs::kLcmBuiltinUrl);
}

TEST_F(BusUrlTest, EnvironmentFileSyntax) {
  write("  export LCM_DEFAULT_URL=\"udpm://239.255.76.67:7667?ttl=1\"  \n# LCM_DEFAULT_URL=x\n");
  EXPECT_EQ(url_in_conf_file(conf_.string()), "udpm://239.255.76.67:7667?ttl=1");
  write("OTHER=1\n");
  EXPECT_EQ(url_in_conf_file(conf_.string()), "");
}

TEST(Bus, ProvidersWithoutMulticastNeedNoRoute) {
  EXPECT_EQ(advee::msgs::multicast_route_problem("memq://"), "");
  EXPECT_NE(advee::msgs::multicast_route_problem("udpm://robot:7667"), "");
}

TEST(Bus, OpensMemq) {
  auto lcm = advee::msgs::open_bus({"memq://", "test"});
  EXPECT_TRUE(lcm->good());
}

}  // namespace
