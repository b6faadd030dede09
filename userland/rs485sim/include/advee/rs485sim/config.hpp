// SPDX-License-Identifier: GPL-2.0
// The simulator's configuration file (YAML): buses, their wires, the devices
// on each with readings, response times and faults. Format: docs/rs485-sim.md.
#pragma once

#include <memory>
#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

#include "advee/config_error.hpp"
#include "advee/rs485sim/bus_sim.hpp"

namespace advee::rs485sim {

// "FILE:LINE: FIELD: what is wrong" (advee/config_error.hpp: one type for
// every configuration file).
using advee::ConfigError;

struct BusConfig {
  std::unique_ptr<BusSim> bus;
  std::string wire;  // e.g. /dev/ts7800-sim/uart0
};

struct SimConfig {
  std::string control;  // control socket path; empty = none
  std::uint32_t seed = 1;
  std::vector<BusConfig> buses;
};

// Throws ConfigError. `name` is used in messages (the file's path); `seed`
// overrides the file's seed.
SimConfig load_config_file(const std::string& path, std::optional<std::uint32_t> seed = std::nullopt);
SimConfig load_config_string(const std::string& yaml, const std::string& name = "<config>",
                             std::optional<std::uint32_t> seed = std::nullopt);

}  // namespace advee::rs485sim
