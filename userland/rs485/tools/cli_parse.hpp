// SPDX-License-Identifier: GPL-2.0
// Parsing of advee-rs485ctl's arguments (numbers, addresses, hex data, durations).
// Every function throws UsageError with a message naming the bad input;
// advee-rs485ctl turns that into exit status 2.
#pragma once

#include <chrono>
#include <cstdint>
#include <stdexcept>
#include <string>
#include <vector>

namespace advee::rs485::cli {

struct UsageError : std::runtime_error {
  using std::runtime_error::runtime_error;
};

// Decimal, 0x hex or 0 octal, the whole string, within [min, max].
std::uint64_t parse_uint(const std::string& text, std::uint64_t min, std::uint64_t max, const std::string& what);
// A node address 0x00..0xFE (or 0xFF if broadcast_ok).
std::uint8_t parse_address(const std::string& text, bool broadcast_ok = false);
// Data bytes from one or more words: "01 02 ff", "0102ff", "0x01,0x02", "de:ad".
std::vector<std::uint8_t> parse_hex_bytes(const std::vector<std::string>& words);
// "10ms", "500us", "2s", "1.5ms"; a bare number is milliseconds.
std::chrono::microseconds parse_duration(const std::string& text);
// "01 02 ff" (empty string for no bytes).
std::string hex(const std::vector<std::uint8_t>& bytes);

}  // namespace advee::rs485::cli
