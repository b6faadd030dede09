// SPDX-License-Identifier: GPL-2.0
// Board readings to LCM messages (pure functions, unit-tested on their own).
#pragma once

#include <vector>

#include "advee/driver_rs485/config.hpp"
#include "advee/driver_rs485/odometry.hpp"
#include "advee/rs485/devices/sbs1.hpp"
#include "advee/rs485/devices/sd1.hpp"
#include "lowlevel/data_beacons_t.hpp"
#include "lowlevel/data_odo_t.hpp"
#include "lowlevel/data_srfs_t.hpp"

namespace advee::driver_rs485 {

// Appends the readings of one BR-SD1 to `m` (ids from the board's sensor
// list; a reading without a distance is -1 m; a configured sensor the board
// did not report is left out) and updates the counts.
void append_ranges(const Sd1Board& board, const rs485::Sd1Distances& d, lowlevel::data_srfs_t& m);

// Tick differences over `interval_s` to an odometry message.
lowlevel::data_odo_t odo_message(const AckermannOdometry& odo, std::int64_t ticks_left,
                                 std::int64_t ticks_right, double interval_s);

lowlevel::data_beacons_t beacons_message(const std::vector<rs485::BeaconBearing>& seen);

}  // namespace advee::driver_rs485
