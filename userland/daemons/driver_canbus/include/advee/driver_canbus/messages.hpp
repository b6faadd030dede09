// SPDX-License-Identifier: GPL-2.0
// DrivesStatus as LL_DATA_DRIVES (lowlevel.data_drives_t).
#pragma once

#include "advee/driver_canbus/controller.hpp"
#include "lowlevel/data_drives_t.hpp"

namespace advee::driver_canbus {

// utime and module are left for the publisher.
lowlevel::data_drives_t drives_message(const DrivesStatus& s);

}  // namespace advee::driver_canbus
