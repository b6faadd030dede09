// SPDX-License-Identifier: GPL-2.0
// advee-canopenctl lss: the arguments of `lss scan`, `lss set-id` and `lss
// identify`, checked with no I/O (canopenctl_lss.cpp, unit-tested), and the
// command run on a master (canopenctl_lss_run.cpp, part of the tool).
#pragma once

#include <array>
#include <cstdint>
#include <functional>
#include <memory>
#include <optional>
#include <string>

#include "advee/canopen/lss_master.hpp"

namespace CLI {
class App;
}

namespace advee::canopen::ctl {

// The raw strings of the command line.
struct LssArgs {
  int answer_ms = 100;
  int settle_ms = 10;
  std::string assign;    // scan --assign FIRST
  std::string vendor, product;  // scan --vendor, --product
  std::string node;      // set-id NODE
  std::string identity;  // set-id --identity
  bool store = false;
};

struct LssCommand {
  std::string name;  // "lss scan", "lss set-id", "lss identify"
  LssMasterConfig config;
  std::optional<std::uint8_t> assign;
  std::array<std::optional<std::uint32_t>, 4> known;  // scan: vendor, product
  std::uint8_t node = 0;
  std::optional<LssAddress> identity;
  bool store = false;
};

// VENDOR:PRODUCT:REVISION:SERIAL, four 32-bit numbers in hex (0x optional).
// Throws UsageError.
LssAddress parse_lss_address(const std::string& s);
// Throws UsageError.
LssCommand check_lss(const std::string& name, const LssArgs& a);
// "vendor 0x000000FB product ... serial 0x00000001 node-ID 10" (no node-ID
// part when none was given).
std::string describe_found(const LssFound& f);

// The CLI11 part and the run (canopenctl_lss_run.cpp).
void describe_lss(CLI::App& app, LssArgs& a);
// Starts the command; end(exit status) is called once when it is over.
// The returned object must live until then.
std::unique_ptr<LssMaster> run_lss(Master& master, const LssCommand& c, std::function<void(int)> end);

}  // namespace advee::canopen::ctl
