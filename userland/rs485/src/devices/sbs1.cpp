// SPDX-License-Identifier: GPL-2.0
#include "advee/rs485/devices/sbs1.hpp"

#include <numbers>

#include "advee/byte_order.hpp"

namespace advee::rs485 {

Expected<std::vector<BeaconBearing>> Sbs1::decode_beacons(std::span<const std::uint8_t> data) {
  constexpr std::size_t kRecord = 4;  // id u8, bearing u16, quality u8
  if (data.empty()) return Outcome::bad_response;
  const std::size_t count = data[0];
  if (data.size() != 1 + kRecord * count) return Outcome::bad_response;
  std::vector<BeaconBearing> out;
  out.reserve(count);
  for (std::size_t i = 0; i < count; ++i) {
    const auto rec = data.subspan(1 + kRecord * i, kRecord);
    const auto centi_deg = load_le<std::uint16_t>(rec.subspan(1, 2));
    if (centi_deg >= sbs1::kBearingUnitsPerTurn) return Outcome::bad_response;
    out.push_back({rec[0], centi_deg * (2 * std::numbers::pi / sbs1::kBearingUnitsPerTurn), rec[3]});
  }
  return out;
}

std::error_code Sbs1::set_beacon_ids(std::span<const std::uint8_t> ids, const CallOptions& options) {
  if (ids.size() > sbs1::kMaxBeaconIds) return std::make_error_code(std::errc::invalid_argument);
  return call_ack(sbs1::instr::kSetBeaconIds, {ids.begin(), ids.end()}, options);
}

Expected<std::vector<BeaconBearing>> Sbs1::beacons(const CallOptions& options) {
  auto r = call(sbs1::instr::kGetBeaconData, {}, options);
  if (!r) return r.error;
  return decode_beacons(r.data);
}

Expected<std::vector<std::uint8_t>> Sbs1::debug_data(const CallOptions& options) {
  auto r = call(sbs1::instr::kGetDebugData, {}, options);
  if (!r) return r.error;
  return std::move(r.data);
}

}  // namespace advee::rs485
