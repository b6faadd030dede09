// SPDX-License-Identifier: GPL-2.0
#include "advee/canopen/drivers/epos.hpp"

#include <cmath>
#include <numbers>

#include "advee/canopen/sdo_sequence.hpp"

namespace advee::canopen::drivers {

namespace {
DriveConfig with_pdos(EposConfig c) {
  DriveConfig d = c.drive;
  d.node = c.node;
  if (d.name == "drive") d.name = "epos";
  d.control_rpdo = 4;
  d.control_entries = {PdoEntry::from_raw(0x60400010), PdoEntry::from_raw(0x60FF0020)};
  d.status_tpdo = 4;
  d.status_entries = {PdoEntry::from_raw(0x60410010), PdoEntry::from_raw(0x606C0020)};
  take_pdos_from_device(d, {0x6040, 0x60FF}, {0x6041, 0x606C});
  return d;
}
}  // namespace

EposDriver::EposDriver(Master& master, EposConfig cfg) : cfg_(cfg), drive_(master, with_pdos(cfg)) {}

void EposDriver::boot(Done done) {
  drive_.boot([this, done](std::error_code ec) {
    if (ec) return done(ec);
    std::vector<SdoWrite> ramps = {
        SdoWrite::of<std::uint32_t>(0x6083, 0, cfg_.acceleration_rpm_s),
        SdoWrite::of<std::uint32_t>(0x6084, 0, cfg_.deceleration_rpm_s),
        SdoWrite::of<std::uint32_t>(0x6085, 0, cfg_.quick_stop_deceleration_rpm_s),
    };
    run_sdo_writes(drive_.sdo(), std::move(ramps), [this, done](const SdoSequenceResult& r) {
      if (r.error) return done(r.error);
      drive_.set_mode(cia402::Mode::kProfileVelocity, done);
    });
  });
}

std::int32_t EposDriver::rpm_for(double v) const {
  const double wheel_rps = v / (2.0 * std::numbers::pi * cfg_.wheel_radius_m);
  return static_cast<std::int32_t>(std::lround(wheel_rps * 60.0 * cfg_.gear_ratio));
}

double EposDriver::m_per_s_for(std::int32_t rpm) const {
  return rpm / 60.0 / cfg_.gear_ratio * 2.0 * std::numbers::pi * cfg_.wheel_radius_m;
}

bool EposDriver::set_speed(double v) { return drive_.set_target(0x60FF, 0, rpm_for(v)); }

std::optional<double> EposDriver::speed() const {
  auto rpm = drive_.feedback(0x606C);
  if (!rpm) return std::nullopt;
  return m_per_s_for(static_cast<std::int32_t>(*rpm));
}

}  // namespace advee::canopen::drivers
