// SPDX-License-Identifier: GPL-2.0
#include "advee/canopen/drivers/icla.hpp"

#include <cmath>

#include "advee/canopen/sdo_sequence.hpp"

namespace advee::canopen::drivers {

namespace {
DriveConfig with_pdos(IclaConfig c) {
  DriveConfig d = c.drive;
  d.node = c.node;
  if (d.name == "drive") d.name = "icla";
  d.control_rpdo = 2;
  d.control_entries = {PdoEntry::from_raw(0x60400010), PdoEntry::from_raw(0x607A0020)};
  d.status_tpdo = 2;
  d.status_entries = {PdoEntry::from_raw(0x60410010), PdoEntry::from_raw(0x60640020)};
  take_pdos_from_device(d, {0x6040, 0x607A}, {0x6041, 0x6064});
  return d;
}
}  // namespace

IclaDriver::IclaDriver(Master& master, IclaConfig cfg) : cfg_(cfg), drive_(master, with_pdos(cfg)) {}

void IclaDriver::boot(Done done) {
  drive_.boot([this, done](std::error_code ec) {
    if (ec) return done(ec);
    run_sdo_writes(drive_.sdo(), {SdoWrite::of<std::uint32_t>(0x6081, 0, cfg_.profile_velocity)},
                   [this, done](const SdoSequenceResult& r) {
                     if (r.error) return done(r.error);
                     drive_.set_mode(cia402::Mode::kProfilePosition, done);
                   });
  });
}

void IclaDriver::home(Done done) {
  std::vector<SdoWrite> setup = {
      SdoWrite::of<std::int8_t>(0x6098, 0, cfg_.homing_method),
      SdoWrite::of<std::uint32_t>(0x6099, 1, cfg_.homing_speed),
      SdoWrite::of<std::uint32_t>(0x609A, 0, cfg_.homing_acceleration),
      SdoWrite::of<std::int32_t>(0x607C, 0, cfg_.home_offset),
  };
  run_sdo_writes(drive_.sdo(), std::move(setup), [this, done](const SdoSequenceResult& r) {
    if (r.error) return done(r.error);
    drive_.set_mode(cia402::Mode::kHoming, [this, done](std::error_code ec) {
      if (ec) return done(ec);
      drive_.home([this, done](std::error_code ec2) {
        // Back to profile position whatever happened, so steering commands work.
        drive_.set_mode(cia402::Mode::kProfilePosition, [done, ec2](std::error_code ec3) { done(ec2 ? ec2 : ec3); });
      });
    });
  });
}

void IclaDriver::set_angle(double rad, Done done) {
  drive_.move_to(static_cast<std::int32_t>(std::lround(rad * cfg_.units_per_rad)), false, std::move(done));
}

std::optional<double> IclaDriver::angle() const {
  auto p = drive_.feedback(0x6064);
  if (!p) return std::nullopt;
  return static_cast<double>(*p) / cfg_.units_per_rad;
}

}  // namespace advee::canopen::drivers
