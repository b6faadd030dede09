// SPDX-License-Identifier: GPL-2.0
// BR-SO1 odometry: two incremental encoders (left, right). The board sends
// signed counters of 1, 2 or 4 bytes that wrap; TickAccumulator turns
// successive readings into 64-bit counts since the last reset, which is
// correct as long as a wheel moves less than half the counter range
// (128, 32768 or 2^31 ticks) between two readings.
#pragma once

#include <cstdint>
#include <optional>
#include <span>

#include "advee/rs485/devices/device.hpp"

namespace advee::rs485 {

namespace so1 {
namespace instr {
inline constexpr std::uint8_t kGetTicks = 0x01;    // width u8 -> 2 x signed counter of that width
inline constexpr std::uint8_t kResetTicks = 0x02;  // -> ACK
}  // namespace instr
inline constexpr unsigned kDefaultWidth = 2;
}  // namespace so1

// One GET_TICKS response, sign-extended (still wrapping in its width).
struct So1RawTicks {
  unsigned width = so1::kDefaultWidth;  // bytes per counter: 1, 2 or 4
  std::int64_t left = 0;
  std::int64_t right = 0;
  friend bool operator==(const So1RawTicks&, const So1RawTicks&) = default;
};

// Accumulated counts since the last reset (ticks, signed).
struct So1Counts {
  std::int64_t left = 0;
  std::int64_t right = 0;
  friend bool operator==(const So1Counts&, const So1Counts&) = default;
};

class TickAccumulator {
 public:
  // The first reading after construction/reset() is taken as the count since
  // the board's reset (it is one: the board counts from 0). Later readings
  // add the difference to the previous one, modulo the reading's width.
  So1Counts update(const So1RawTicks& raw);
  const So1Counts& counts() const { return counts_; }
  void reset();

 private:
  std::optional<So1RawTicks> last_;
  So1Counts counts_;
};

class So1 : public Device {
 public:
  using Device::Device;

  // One GET_TICKS reading as the board sent it. width: 1, 2 or 4 (else EINVAL).
  Expected<So1RawTicks> raw_ticks(unsigned width = so1::kDefaultWidth, const CallOptions& options = {});
  // raw_ticks() fed to the accumulator: 64-bit counts since reset().
  Expected<So1Counts> counts(unsigned width = so1::kDefaultWidth, const CallOptions& options = {});
  // RESET_TICKS on the board and the accumulator set to 0.
  std::error_code reset_ticks(const CallOptions& options = {});
  const TickAccumulator& accumulator() const { return accumulator_; }

  // Outcome::bad_response unless the data is exactly 2 x width bytes;
  // std::errc::invalid_argument for a width other than 1, 2, 4.
  static Expected<So1RawTicks> decode_ticks(std::span<const std::uint8_t> data, unsigned width);

 private:
  TickAccumulator accumulator_;
};

}  // namespace advee::rs485
