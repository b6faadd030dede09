// SPDX-License-Identifier: GPL-2.0
// Configuration of one driver_rs485 instance (one bus): the bus, the polling
// rate and the boards on it. Bus A of the robot has two BR-SD1 and the BR-SO1
// (4 Hz), bus B the BR-SBS1 (1 Hz); any mix is accepted. docs/daemons.md.
#pragma once

#include <chrono>
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "advee/driver_rs485/odometry.hpp"
#include "advee/module/config.hpp"
#include "advee/rs485_daemon/bus_section.hpp"

namespace advee::driver_rs485 {

// One ultrasonic or infrared sensor behind a BR-SD1 (thesis: srfs.txt).
struct RangeSensor {
  unsigned index = 0;  // reading index on the board (SRF 0..7, IR 0..1)
  int id = 0;          // id on LL_DATA_SRFS
  double x_m = 0, y_m = 0;    // mounting position, robot frame (x forward, y left)
  double heading_rad = 0;     // direction of the beam, counter-clockwise from x
};

struct Sd1Board {
  std::string name;            // "front", "rear" (messages and reports)
  std::uint8_t address = 0;
  // Empty: every reading the board sends, id = first_srf_id + index (the
  // same for the IR sensors with first_ir_id).
  std::vector<RangeSensor> srfs, irs;
  int first_srf_id = 0, first_ir_id = 0;
};

struct So1Board {
  std::uint8_t address = 0;
  unsigned width = 2;          // GET_TICKS counter width in bytes: 1, 2, 4
  // Fastest ground speed of an encoder wheel (the chassis' top speed): sets
  // how long a gap between readings may be before a wrap could hide in it.
  double max_speed_mps = 1.5;
  ChassisGeometry geometry;
};

struct Sbs1Board {
  std::uint8_t address = 0;
  std::vector<std::uint8_t> beacon_ids;  // applied at start (LL_DATA_ACTIVE_BEACONS replaces them)
  std::chrono::milliseconds resend_ids{10000};  // SET_BEACON_IDS again (a board that reset forgets them)
};

struct Rs485Config {
  module::ModuleOptions module;
  rs485_daemon::BusSection bus;
  double rate_hz = 4.0;
  std::vector<Sd1Board> sd1;
  std::optional<So1Board> so1;
  std::optional<Sbs1Board> sbs1;
};

// Throws module::ConfigError naming file:line: key.
Rs485Config parse_rs485_config(const module::ConfigNode& root);

}  // namespace advee::driver_rs485
