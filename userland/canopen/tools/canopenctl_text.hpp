// SPDX-License-Identifier: GPL-2.0
// advee-canopenctl's arguments and output as text, with no I/O: node-IDs, objects,
// SDO types and values (range-checked), and the monitor's one-line frame
// description. Unit-tested (canopenctl_test.cpp); the tool checks every
// argument with these before it opens the CAN socket.
#pragma once

#include <array>
#include <cstdint>
#include <optional>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#include "advee/canopen/frame.hpp"
#include "advee/canopen/pdo.hpp"

namespace advee::canopen::ctl {

// A usage error: advee-canopenctl prints it and exits 2.
struct UsageError : std::invalid_argument {
  using std::invalid_argument::invalid_argument;
};

struct SdoType {
  const char* name;
  int size;  // bytes; 0: variable (str, hex)
  bool is_signed;
};
// u8 u16 u32 u64 i8 i16 i32 i64 str hex
const std::vector<SdoType>& sdo_types();

// 1..127, or 0 for "all" when allowed. Throw UsageError.
std::uint8_t parse_node(const std::string& s, bool allow_all = false);
// NODE or FIRST-LAST (1..127, FIRST <= LAST). Throws UsageError.
std::pair<std::uint8_t, std::uint8_t> parse_node_range(const std::string& s);
// INDEX[:SUB], index in hex, sub-index decimal or 0x-hex.
std::pair<std::uint16_t, std::uint8_t> parse_object(const std::string& s);
const SdoType& parse_type(const std::string& s);
// `pdo remap`: KIND rpdo|tpdo, NUMBER 1..4, entries INDEX:SUB/BITS (1..64
// bits each, at most 64 in all, at most 8 entries); the mapping gets the
// node's predefined COB-ID (valid) and transmission type 255.
PdoMapping parse_pdo_remap(std::uint8_t node, const std::string& kind, const std::string& number,
                           const std::vector<std::string>& entries);
// The value's bytes for the type; numbers must fit the type (i8 300 is an
// error, not 0x2C), hex needs pairs of hex digits.
std::vector<std::uint8_t> encode(const SdoType& t, const std::string& v);
std::string format(const SdoType& t, const std::vector<std::uint8_t>& d);

// "201#0F00  RPDO1 node 1": the frame and what it is by its COB-ID.
std::string describe_frame(const CanFrame& f);
// "heartbeat node 5 operational" for a heartbeat or boot-up frame.
std::optional<std::string> describe_heartbeat(const CanFrame& f);

// What `scan` learns of a node: 0x1000 and the identity object 0x1018
// (sub-indices 1..4; a device need not have 2..4).
struct Identity {
  std::uint32_t device_type = 0;
  std::array<std::optional<std::uint32_t>, 4> identity;  // vendor, product, revision, serial
};
std::string describe_identity(std::uint8_t node, const Identity& id);

}  // namespace advee::canopen::ctl
