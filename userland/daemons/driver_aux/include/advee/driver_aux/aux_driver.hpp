// SPDX-License-Identifier: GPL-2.0
// driver_aux (thesis 7.2.2): the computer box's MAX6615 through its hwmon
// driver. At `rate_hz` it reads the temperatures and fans and publishes
// LL_DATA_TEMPERATURE and LL_DATA_FANS (with the fan-fail GPIO line when one
// is configured); an optional fan policy drives the PWM outputs from the
// hottest temperature instead of the chip's automatic mode.
#pragma once

#include <chrono>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "advee/driver_aux/gpio_input.hpp"
#include "advee/driver_aux/hwmon.hpp"
#include "advee/module/config.hpp"
#include "advee/module/module.hpp"

namespace advee::driver_aux {

// Linear fan curve: duty `min_pwm` at or below `low_c`, 255 at or above
// `high_c`, linear in between.
struct FanPolicy {
  bool enabled = false;
  double low_c = 35.0;
  double high_c = 60.0;
  int min_pwm = 64;
  std::vector<std::string> pwms{"pwm1", "pwm2"};
  int duty_for(double hottest_c) const;
};

struct FanFailLine {
  std::string line_name;  // by name (preferred), or
  std::string chip;       // chip + offset
  unsigned offset = 0;
  bool active_low = true;  // the MAX6615 FAN_FAIL output is open-drain, active low
};

struct AuxConfig {
  module::ModuleOptions module;
  std::string hwmon_name = "max6615";
  std::string hwmon_root = "/sys/class/hwmon";
  double rate_hz = 1.0;
  std::vector<std::string> temperatures;  // empty: every tempN_input
  std::vector<std::string> fans;          // empty: every fanN_input
  std::optional<FanFailLine> fan_fail;
  FanPolicy policy;
};

// Throws module::ConfigError.
AuxConfig parse_aux_config(const module::ConfigNode& root);

// Exit details of driver_aux (module::ExitKind::Device + n).
inline constexpr int kExitNoHwmon = 1;      // no hwmon device with the configured name
inline constexpr int kExitHwmonGone = 2;    // the device disappeared while running
inline constexpr int kExitNoFanFail = 3;    // the fan-fail line cannot be requested
inline constexpr int kExitNoChannel = 4;    // a configured channel does not exist

class AuxDriver {
 public:
  // Finds the device and the line (throws module::ModuleExit with the codes
  // above) and registers the periodic poll on `m`.
  AuxDriver(module::Module& m, AuxConfig cfg);
  ~AuxDriver();  // gives the PWM outputs back to the chip's automatic mode

  void poll();  // one read + publish (called by the module loop in RUN)
  const HwmonDevice& device() const { return dev_; }

 private:
  void apply_policy(double hottest_c);
  void restore_pwm_modes();

  module::Module& m_;
  AuxConfig cfg_;
  HwmonDevice dev_;
  std::vector<std::string> temps_, fans_;
  std::optional<GpioInput> fan_fail_;
  bool fan_fail_was_ = false;
  std::vector<std::pair<std::string, long>> saved_pwm_modes_;  // policy: pwmN_enable before
};

}  // namespace advee::driver_aux
