// SPDX-License-Identifier: GPL-2.0
// Every LCM channel of the low level in one place (thesis 3.4.2: prefix
// LL/CM, type CMD/DATA/EVENT, name), with the message type it carries and its
// nominal rate. rate_hz 0 = sent when something happens (commands, events).
#pragma once

#include <array>
#include <string_view>

namespace advee::msgs {

struct Channel {
  std::string_view name;
  std::string_view type;  // LCM type, package.name
  double rate_hz;         // nominal publishing rate, 0 = aperiodic
};

inline constexpr Channel kDataState{"CM_DATA_STATE", "common.data_state_t", 1.0};  // per module
inline constexpr Channel kCmdState{"CM_CMD_STATE", "common.cmd_state_t", 0};
inline constexpr Channel kDataError{"CM_DATA_ERROR", "common.error_t", 0};
inline constexpr Channel kDataModules{"CM_DATA_MODULES", "common.data_module_phase_t", 0};
inline constexpr Channel kDataSrfs{"LL_DATA_SRFS", "lowlevel.data_srfs_t", 4.0};
inline constexpr Channel kDataOdo{"LL_DATA_ODO", "lowlevel.data_odo_t", 4.0};
inline constexpr Channel kDataBeacons{"LL_DATA_BEACONS", "lowlevel.data_beacons_t", 1.0};
inline constexpr Channel kDataActiveBeacons{"LL_DATA_ACTIVE_BEACONS",
                                            "lowlevel.data_active_beacons_t", 0};
inline constexpr Channel kCmdMotion{"LL_CMD_MOTION", "lowlevel.cmd_motion_t", 0};  // > 1 Hz
inline constexpr Channel kCmdHoming{"LL_CMD_HOMING", "lowlevel.cmd_homing_t", 0};
inline constexpr Channel kCmdPower{"LL_CMD_POWER", "lowlevel.cmd_power_t", 0};
inline constexpr Channel kDataPower{"LL_DATA_POWER", "lowlevel.data_power_t", 1.0};
inline constexpr Channel kEventStop{"LL_EVENT_STOP", "lowlevel.event_stop_t", 0};
inline constexpr Channel kDataTemperature{"LL_DATA_TEMPERATURE", "lowlevel.data_temperature_t",
                                          1.0};
inline constexpr Channel kDataFans{"LL_DATA_FANS", "lowlevel.data_fans_t", 1.0};
inline constexpr Channel kDataDrives{"LL_DATA_DRIVES", "lowlevel.data_drives_t", 4.0};

inline constexpr std::array kAllChannels{
    kDataState, kCmdState,  kDataError,         kDataModules, kDataSrfs,
    kDataOdo,   kDataBeacons, kDataActiveBeacons, kCmdMotion,   kCmdHoming,
    kCmdPower,  kDataPower, kEventStop,         kDataTemperature, kDataFans,
    kDataDrives,
};

}  // namespace advee::msgs
