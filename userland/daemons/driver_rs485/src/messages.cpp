// SPDX-License-Identifier: GPL-2.0
#include "advee/driver_rs485/messages.hpp"

namespace advee::driver_rs485 {

namespace {

void append(const std::vector<RangeSensor>& listed, int first_id,
            const std::vector<std::optional<double>>& readings, std::vector<std::int16_t>& ids,
            std::vector<float>& ranges) {
  const auto range = [](const std::optional<double>& r) { return r ? static_cast<float>(*r) : -1.0f; };
  if (listed.empty()) {
    for (std::size_t i = 0; i < readings.size(); ++i) {
      ids.push_back(static_cast<std::int16_t>(first_id + static_cast<int>(i)));
      ranges.push_back(range(readings[i]));
    }
    return;
  }
  for (const auto& s : listed) {
    if (s.index >= readings.size()) continue;
    ids.push_back(static_cast<std::int16_t>(s.id));
    ranges.push_back(range(readings[s.index]));
  }
}

}  // namespace

void append_ranges(const Sd1Board& board, const rs485::Sd1Distances& d, lowlevel::data_srfs_t& m) {
  append(board.srfs, board.first_srf_id, d.srf_m, m.srf_id, m.srf_range_m);
  append(board.irs, board.first_ir_id, d.ir_m, m.ir_id, m.ir_range_m);
  m.num_srfs = static_cast<std::int16_t>(m.srf_id.size());
  m.num_irs = static_cast<std::int16_t>(m.ir_id.size());
}

lowlevel::data_odo_t odo_message(const AckermannOdometry& odo, std::int64_t ticks_left,
                                 std::int64_t ticks_right, double interval_s) {
  lowlevel::data_odo_t m{};
  m.ticks_left = static_cast<std::int32_t>(ticks_left);
  m.ticks_right = static_cast<std::int32_t>(ticks_right);
  m.interval_s = interval_s;
  const auto s = odo.from_ticks(static_cast<double>(ticks_left), static_cast<double>(ticks_right), interval_s);
  m.speed_mps = s.speed_mps;
  m.yaw_rate_radps = s.yaw_rate_radps;
  return m;
}

lowlevel::data_beacons_t beacons_message(const std::vector<rs485::BeaconBearing>& seen) {
  lowlevel::data_beacons_t m{};
  for (const auto& b : seen) {
    m.id.push_back(b.id);
    m.bearing_rad.push_back(static_cast<float>(b.bearing_rad));
  }
  m.count = static_cast<std::int16_t>(m.id.size());
  return m;
}

}  // namespace advee::driver_rs485
