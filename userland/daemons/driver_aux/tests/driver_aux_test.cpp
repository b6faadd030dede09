// SPDX-License-Identifier: GPL-2.0
// driver_aux against a hwmon tree built in a temporary directory (same
// layout as /sys/class/hwmon): device lookup by name, published values,
// PAUSE stopping the publication, the fan policy, configuration errors and
// the exit codes of a missing or vanished device.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <lcm/lcm-cpp.hpp>
#include <vector>

#include "advee/driver_aux/aux_driver.hpp"
#include "advee/module/manual_loop.hpp"
#include "advee/module/subscription.hpp"
#include "lowlevel/data_fans_t.hpp"
#include "lowlevel/data_temperature_t.hpp"

using namespace advee;
using namespace advee::driver_aux;
using namespace std::chrono_literals;
namespace fs = std::filesystem;

namespace {

class FakeHwmon : public testing::Test {
 protected:
  void SetUp() override {
    root_ = fs::temp_directory_path() / ("advee-hwmon-" + std::to_string(::getpid()) + "-" +
                                         testing::UnitTest::GetInstance()->current_test_info()->name());
    fs::remove_all(root_);
    // hwmon0 is another chip; the MAX6615 is hwmon1.
    put("hwmon0/name", "coretemp");
    put("hwmon0/temp1_input", "99000");
    put("hwmon1/name", "max6615");
    put("hwmon1/temp1_input", "39625");
    put("hwmon1/temp2_input", "45125");
    put("hwmon1/fan1_input", "975");
    put("hwmon1/fan2_input", "900");
    put("hwmon1/fan1_fault", "0");
    put("hwmon1/fan2_fault", "1");
    put("hwmon1/pwm1", "51");
    put("hwmon1/pwm2", "51");
    put("hwmon1/pwm1_enable", "2");
    put("hwmon1/pwm2_enable", "2");
  }
  void TearDown() override { fs::remove_all(root_); }
  void put(const std::string& rel, const std::string& v) {
    fs::create_directories((root_ / rel).parent_path());
    std::ofstream(root_ / rel) << v << "\n";
  }
  std::string get(const std::string& rel) {
    std::ifstream f(root_ / rel);
    std::string s;
    std::getline(f, s);
    return s;
  }
  AuxConfig config(const std::string& extra = "") {
    auto c = parse_aux_config(module::ConfigNode::parse(
        "module: {lcm_url: 'memq://', print_severity: none}\n"
        "driver_aux:\n  hwmon_root: " + root_.string() + "\n  rate_hz: 50\n" + extra));
    return c;
  }

  fs::path root_;
};

struct Rx {
  std::vector<lowlevel::data_temperature_t> temps;
  std::vector<lowlevel::data_fans_t> fans;
};

// The modules run on a manual clock: `d` of module time in 1 ms steps, each
// followed by the loop passes that handle what became ready (memq delivers
// on the pass after a publish). No wall-clock wait.
module::ManualTimers clock_;
void spin(module::Module& m, std::chrono::milliseconds d) { module::run_manual(m, clock_, d); }

TEST_F(FakeHwmon, FindsTheDeviceByName) {
  auto d = HwmonDevice::find(root_, "max6615");
  ASSERT_TRUE(d);
  EXPECT_EQ(d->dir().filename(), "hwmon1");
  EXPECT_EQ(d->channels("temp"), (std::vector<std::string>{"temp1", "temp2"}));
  EXPECT_EQ(d->read("temp2_input"), 45125);
  EXPECT_FALSE(d->read("temp3_input"));
  EXPECT_FALSE(HwmonDevice::find(root_, "max6639"));
  EXPECT_FALSE(HwmonDevice::find(root_ / "nonexistent", "max6615"));
}

TEST_F(FakeHwmon, PublishesTemperaturesAndFansWhileRunning) {
  auto cfg = config();
  module::Module m(cfg.module, clock_);
  Rx rx;
  module::Subscription<lowlevel::data_temperature_t> st(m.lcm(), "LL_DATA_TEMPERATURE", [&](const auto& x) { rx.temps.push_back(x); });
  module::Subscription<lowlevel::data_fans_t> sf(m.lcm(), "LL_DATA_FANS", [&](const auto& x) { rx.fans.push_back(x); });
  AuxDriver d(m, cfg);
  m.request_state(module::State::Run, false, "test");
  spin(m, 150ms);
  ASSERT_FALSE(rx.temps.empty());
  const auto& t = rx.temps.back();
  EXPECT_EQ(t.module, "driver_aux");
  EXPECT_EQ(t.label, (std::vector<std::string>{"temp1", "temp2"}));
  EXPECT_EQ(t.celsius, (std::vector<float>{39.625f, 45.125f}));
  ASSERT_FALSE(rx.fans.empty());
  const auto& f = rx.fans.back();
  EXPECT_EQ(f.rpm, (std::vector<std::int32_t>{975, 900}));
  EXPECT_EQ(f.fault, (std::vector<std::int8_t>{0, 1}));
  EXPECT_EQ(f.pwm, (std::vector<std::int16_t>{51, 51}));
  EXPECT_FALSE(f.fan_fail);

  // A new reading is published on the next poll.
  put("hwmon1/temp1_input", "52250");
  spin(m, 100ms);
  EXPECT_FLOAT_EQ(rx.temps.back().celsius[0], 52.25f);

  // PAUSE stops publishing.
  m.request_state(module::State::Pause, false, "test");
  spin(m, 30ms);
  const auto n = rx.temps.size();
  spin(m, 150ms);
  EXPECT_EQ(rx.temps.size(), n);
  // 50 Hz for ~250 ms of RUN; the policy is off: nothing written.
  EXPECT_EQ(get("hwmon1/pwm1_enable"), "2");
}

TEST_F(FakeHwmon, FanPolicyDrivesPwmAndGivesBackAutomaticMode) {
  auto cfg = config("  fan_policy: {enabled: true, low_c: 30, high_c: 50, min_pwm: 55}\n");
  EXPECT_EQ(cfg.policy.duty_for(20), 55);
  EXPECT_EQ(cfg.policy.duty_for(40), 155);
  EXPECT_EQ(cfg.policy.duty_for(70), 255);
  {
    module::Module m(cfg.module, clock_);
    AuxDriver d(m, cfg);
    m.request_state(module::State::Run, false, "test");
    spin(m, 60ms);
    // hottest 45.125 C -> 55 + 200 * 15.125 / 20 = 206.25 -> 206
    EXPECT_EQ(get("hwmon1/pwm1_enable"), "1");
    EXPECT_EQ(get("hwmon1/pwm1"), "206");
    EXPECT_EQ(get("hwmon1/pwm2"), "206");
  }
  EXPECT_EQ(get("hwmon1/pwm1_enable"), "2");
  EXPECT_EQ(get("hwmon1/pwm2_enable"), "2");
}

TEST_F(FakeHwmon, MissingDeviceIsADeviceExit) {
  auto cfg = config();
  cfg.hwmon_name = "max6616";
  module::Module m(cfg.module, clock_);
  try {
    AuxDriver d(m, cfg);
    FAIL() << "no exception";
  } catch (const module::ModuleExit& e) {
    EXPECT_EQ(e.code(), 0x21);
    EXPECT_NE(std::string(e.what()).find("no hwmon device named 'max6616'"), std::string::npos);
  }
}

TEST_F(FakeHwmon, MissingChannelIsADeviceExit) {
  auto cfg = config("  temperatures: [temp1, temp3]\n");
  module::Module m(cfg.module, clock_);
  try {
    AuxDriver d(m, cfg);
    FAIL() << "no exception";
  } catch (const module::ModuleExit& e) {
    EXPECT_EQ(e.code(), 0x24);
  }
}

TEST_F(FakeHwmon, UnknownFanFailLineIsADeviceExit) {
  auto cfg = config("  fan_fail: {line: NO_SUCH_LINE_ADVEE}\n");
  module::Module m(cfg.module, clock_);
  try {
    AuxDriver d(m, cfg);
    FAIL() << "no exception";
  } catch (const module::ModuleExit& e) {
    EXPECT_EQ(e.code(), 0x23);
  }
}

TEST_F(FakeHwmon, VanishedDeviceEndsTheModuleWithItsCode) {
  auto cfg = config();
  module::Module m(cfg.module, clock_);
  AuxDriver d(m, cfg);
  // The driver unbound: its hwmon directory is gone.
  fs::remove_all(root_ / "hwmon1");
  clock_.advance(20ms);  // the first poll at 50 Hz
  EXPECT_EQ(m.run(), 0x22);
}

TEST_F(FakeHwmon, UnreadableAttributeEndsTheModuleWithItsCode) {
  auto cfg = config();
  module::Module m(cfg.module, clock_);
  AuxDriver d(m, cfg);
  // A read error other than ENODATA (here EISDIR) is a device failure.
  fs::remove(root_ / "hwmon1/temp1_input");
  fs::create_directory(root_ / "hwmon1/temp1_input");
  clock_.advance(20ms);
  EXPECT_EQ(m.run(), 0x22);
}

TEST(AuxConfig, Errors) {
  auto err = [](const std::string& y) -> std::string {
    try {
      parse_aux_config(module::ConfigNode::parse(y, "aux.yaml"));
    } catch (const module::ConfigError& e) {
      return e.what();
    }
    return "";
  };
  EXPECT_EQ(err("driver_aux: {rate_hz: 0}\n"), "aux.yaml:1: rate_hz: must be between 0.1 and 50");
  EXPECT_EQ(err("driver_aux:\n  fan_fail: {line: DIO_7, chip: gpiochip0}\n"),
            "aux.yaml:2: line: give either line (a name) or chip + offset");
  EXPECT_EQ(err("driver_aux:\n  fan_fail: {chip: gpiochip0}\n"), "aux.yaml:2: offset: missing");
  EXPECT_EQ(err("driver_aux:\n  fans: fan1\n"), "aux.yaml:2: fans: expected a list such as [temp1, temp2]");
  EXPECT_EQ(err("driver_aux:\n  fan_policy: {low_c: 50, high_c: 40}\n"), "aux.yaml:2: high_c: must be above low_c");
  EXPECT_EQ(err("driver_aux:\n  hwmon: max6615\n"), "aux.yaml:2: hwmon: unknown key");
  const auto c = parse_aux_config(module::ConfigNode::parse("{}"));
  EXPECT_EQ(c.hwmon_name, "max6615");
  EXPECT_EQ(c.hwmon_root, "/sys/class/hwmon");
  EXPECT_EQ(c.module.name, "driver_aux");
  EXPECT_FALSE(c.fan_fail);
  EXPECT_FALSE(c.policy.enabled);
}

}  // namespace
