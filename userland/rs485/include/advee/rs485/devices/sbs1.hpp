// SPDX-License-Identifier: GPL-2.0
// BR-SBS1 infrared beacon scanner: which beacon ids to look for, and the
// bearings of the beacons seen. Bearings in radians, [0, 2*pi),
// counter-clockwise from the robot's heading (the board sends 0.01 degree).
#pragma once

#include <cstdint>
#include <span>
#include <vector>

#include "advee/rs485/devices/device.hpp"

namespace advee::rs485 {

namespace sbs1 {
namespace instr {
inline constexpr std::uint8_t kSetBeaconIds = 0x01;   // k u8 ids -> ACK
inline constexpr std::uint8_t kGetBeaconData = 0x02;  // -> c u8, c x {id u8, bearing u16, quality u8}
inline constexpr std::uint8_t kGetDebugData = 0x03;   // -> opaque
}  // namespace instr
inline constexpr std::uint16_t kBearingUnitsPerTurn = 36000;  // 0.01 degree
inline constexpr std::size_t kMaxBeaconIds = 255;
}  // namespace sbs1

struct BeaconBearing {
  std::uint8_t id = 0;
  double bearing_rad = 0;   // [0, 2*pi), counter-clockwise from the heading
  std::uint8_t quality = 0; // as the board reports it (higher = better)
};

class Sbs1 : public Device {
 public:
  using Device::Device;

  // At most 255 ids (EINVAL above).
  std::error_code set_beacon_ids(std::span<const std::uint8_t> ids, const CallOptions& options = {});
  Expected<std::vector<BeaconBearing>> beacons(const CallOptions& options = {});
  Expected<std::vector<std::uint8_t>> debug_data(const CallOptions& options = {});

  // Outcome::bad_response unless the data is c and exactly c records, each
  // bearing within 0..35999.
  static Expected<std::vector<BeaconBearing>> decode_beacons(std::span<const std::uint8_t> data);
};

}  // namespace advee::rs485
