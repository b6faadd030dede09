// SPDX-License-Identifier: GPL-2.0
#include "advee/driver_aux/aux_driver.hpp"

#include <algorithm>
#include <cmath>
#include <lcm/lcm-cpp.hpp>
#include <system_error>

#include "advee/module/time.hpp"
#include "advee/msgs/channels.hpp"
#include "lowlevel/data_fans_t.hpp"
#include "lowlevel/data_temperature_t.hpp"

namespace advee::driver_aux {

using module::ConfigNode;
using module::ErrorType;
using module::ExitKind;
using module::ModuleExit;
using module::Severity;

int FanPolicy::duty_for(double t) const {
  if (t <= low_c) return min_pwm;
  if (t >= high_c) return 255;
  return static_cast<int>(std::lround(min_pwm + (255 - min_pwm) * (t - low_c) / (high_c - low_c)));
}

AuxConfig parse_aux_config(const ConfigNode& root) {
  root.allow_only({"module", "driver_aux"});
  AuxConfig c;
  c.module.name = "driver_aux";
  if (root.has("module")) module::parse_module_options(root.child("module"), c.module);
  if (!root.has("driver_aux")) return c;
  const auto n = root.child("driver_aux");
  n.allow_only({"hwmon_name", "hwmon_root", "rate_hz", "temperatures", "fans", "fan_fail", "fan_policy"});
  c.hwmon_name = n.get<std::string>("hwmon_name", c.hwmon_name);
  c.hwmon_root = n.get<std::string>("hwmon_root", c.hwmon_root);
  c.rate_hz = n.get<double>("rate_hz", c.rate_hz);
  if (!(c.rate_hz >= 0.1 && c.rate_hz <= 50)) n.fail("rate_hz", "must be between 0.1 and 50");
  for (const char* key : {"temperatures", "fans"}) {
    if (!n.has(key)) continue;
    if (!n.yaml()[key].IsSequence()) n.fail(key, "expected a list such as [temp1, temp2]");
    (std::string(key) == "fans" ? c.fans : c.temperatures) = n.get<std::vector<std::string>>(key);
  }
  if (n.has("fan_fail")) {
    const auto f = n.child("fan_fail");
    f.allow_only({"line", "chip", "offset", "active_low"});
    FanFailLine l;
    l.line_name = f.get<std::string>("line", "");
    l.chip = f.get<std::string>("chip", "");
    if (l.line_name.empty() == l.chip.empty()) f.fail("line", "give either line (a name) or chip + offset");
    if (!l.chip.empty()) l.offset = f.get<unsigned>("offset");
    l.active_low = f.get<bool>("active_low", true);
    c.fan_fail = l;
  }
  if (n.has("fan_policy")) {
    const auto p = n.child("fan_policy");
    p.allow_only({"enabled", "low_c", "high_c", "min_pwm", "pwms"});
    c.policy.enabled = p.get<bool>("enabled", false);
    c.policy.low_c = p.get<double>("low_c", c.policy.low_c);
    c.policy.high_c = p.get<double>("high_c", c.policy.high_c);
    if (!(c.policy.high_c > c.policy.low_c)) p.fail("high_c", "must be above low_c");
    c.policy.min_pwm = p.get<int>("min_pwm", c.policy.min_pwm);
    if (c.policy.min_pwm < 0 || c.policy.min_pwm > 255) p.fail("min_pwm", "must be 0..255");
    if (p.has("pwms")) c.policy.pwms = p.get<std::vector<std::string>>("pwms");
  }
  return c;
}

AuxDriver::AuxDriver(module::Module& m, AuxConfig cfg)
    : m_(m), cfg_(std::move(cfg)), dev_([&] {
        auto d = HwmonDevice::find(cfg_.hwmon_root, cfg_.hwmon_name);
        if (!d)
          throw ModuleExit(ExitKind::Device, kExitNoHwmon,
                           "no hwmon device named '" + cfg_.hwmon_name + "' under " +
                               cfg_.hwmon_root +
                               " (is the max6615 driver loaded and the chip detected? "
                               "see docs/hwmon/max6615.rst)");
        return *d;
      }()) {
  temps_ = cfg_.temperatures.empty() ? dev_.channels("temp") : cfg_.temperatures;
  fans_ = cfg_.fans.empty() ? dev_.channels("fan") : cfg_.fans;
  for (const auto& ch : temps_)
    if (!dev_.has(ch + "_input"))
      throw ModuleExit(ExitKind::Device, kExitNoChannel, dev_.dir().string() + " has no " + ch + "_input");
  for (const auto& ch : fans_)
    if (!dev_.has(ch + "_input"))
      throw ModuleExit(ExitKind::Device, kExitNoChannel, dev_.dir().string() + " has no " + ch + "_input");
  if (cfg_.fan_fail) {
    const auto& l = *cfg_.fan_fail;
    try {
      fan_fail_ = l.line_name.empty()
                      ? GpioInput::by_offset(l.chip, l.offset, l.active_low, m_.name())
                      : GpioInput::by_name(l.line_name, l.active_low, m_.name());
    } catch (const std::system_error& e) {
      throw ModuleExit(ExitKind::Device, kExitNoFanFail, std::string("fan-fail line: ") + e.what());
    }
  }
  if (cfg_.policy.enabled) {
    for (const auto& pwm : cfg_.policy.pwms) {
      const auto mode = dev_.read(pwm + "_enable");
      if (!mode)
        throw ModuleExit(ExitKind::Device, kExitNoChannel, dev_.dir().string() + " has no " + pwm + "_enable");
      saved_pwm_modes_.emplace_back(pwm, *mode);
    }
  }
  m_.errors().report(Severity::Notice, ErrorType::Unknown, 0,
                     "using " + dev_.dir().string() +
                         (fan_fail_ ? ", fan-fail " + fan_fail_->description() : std::string()) +
                         (cfg_.policy.enabled ? ", fan policy on" : ""));
  m_.every(std::chrono::nanoseconds(static_cast<std::int64_t>(1e9 / cfg_.rate_hz)), [this] { poll(); });
}

AuxDriver::~AuxDriver() { restore_pwm_modes(); }

void AuxDriver::restore_pwm_modes() {
  for (const auto& [pwm, mode] : saved_pwm_modes_) {
    try {
      dev_.write(pwm + "_enable", mode);
    } catch (const std::system_error&) {
      // The device is gone; nothing left to give back.
    }
  }
  saved_pwm_modes_.clear();
}

void AuxDriver::poll() {
  lowlevel::data_temperature_t t;
  lowlevel::data_fans_t f;
  // An unbound driver takes its hwmonN directory along: every attribute would
  // read as "no data", so check for the device itself.
  if (!dev_.has("name"))
    throw ModuleExit(ExitKind::Device, kExitHwmonGone, dev_.dir().string() + " disappeared");
  try {
    t.utime = module::utime_now();
    t.module = m_.name();
    double hottest = -1000;
    for (const auto& ch : temps_) {
      const auto v = dev_.read(ch + "_input");
      if (!v) continue;  // no reading this time (ENODATA)
      t.label.push_back(ch);
      t.celsius.push_back(static_cast<float>(*v / 1000.0));
      hottest = std::max(hottest, *v / 1000.0);
    }
    t.count = static_cast<std::int16_t>(t.label.size());

    f.utime = t.utime;
    f.module = m_.name();
    for (const auto& ch : fans_) {
      f.label.push_back(ch);
      const auto rpm = dev_.read(ch + "_input");
      f.rpm.push_back(rpm ? static_cast<std::int32_t>(*rpm) : -1);
      f.fault.push_back(dev_.read(ch + "_fault").value_or(0) != 0);
      // fanN drives from pwmN on the MAX6615.
      const auto pwm = dev_.read("pwm" + ch.substr(3));
      f.pwm.push_back(pwm ? static_cast<std::int16_t>(*pwm) : -1);
    }
    f.count = static_cast<std::int16_t>(f.label.size());
    if (cfg_.policy.enabled && hottest > -1000) apply_policy(hottest);
  } catch (const std::system_error& e) {
    throw ModuleExit(ExitKind::Device, kExitHwmonGone, std::string("hwmon read failed: ") + e.what());
  }
  f.fan_fail = false;
  if (fan_fail_) {
    try {
      f.fan_fail = fan_fail_->asserted();
    } catch (const std::system_error& e) {
      throw ModuleExit(ExitKind::Device, kExitNoFanFail, e.what());
    }
    if (f.fan_fail != fan_fail_was_)
      m_.errors().report(f.fan_fail ? Severity::Warning : Severity::Notice, ErrorType::Device, 0,
                         f.fan_fail ? "fan failure signalled on " + fan_fail_->description()
                                    : "fan-fail line released");
    fan_fail_was_ = f.fan_fail;
  }
  m_.lcm().publish(std::string(msgs::kDataTemperature.name), &t);
  m_.lcm().publish(std::string(msgs::kDataFans.name), &f);
}

void AuxDriver::apply_policy(double hottest_c) {
  const int duty = cfg_.policy.duty_for(hottest_c);
  for (const auto& pwm : cfg_.policy.pwms) {
    if (dev_.read(pwm + "_enable").value_or(0) != 1) dev_.write(pwm + "_enable", 1);
    if (dev_.read(pwm).value_or(-1) != duty) dev_.write(pwm, duty);
  }
}

}  // namespace advee::driver_aux
