// SPDX-License-Identifier: GPL-2.0
#include "advee/rs485/devices/so1.hpp"

#include "advee/byte_order.hpp"

namespace advee::rs485 {
namespace {

bool valid_width(unsigned width) { return width == 1 || width == 2 || width == 4; }

std::int64_t load_signed(std::span<const std::uint8_t> bytes, unsigned width) {
  switch (width) {
    case 1: return load_le<std::int8_t>(bytes);
    case 2: return load_le<std::int16_t>(bytes);
    default: return load_le<std::int32_t>(bytes);
  }
}

// (now - before) modulo 2^(8 width), as the signed difference closest to 0.
// Computed in uint64 so that no step overflows.
std::int64_t wrap_delta(std::int64_t now, std::int64_t before, unsigned width) {
  const unsigned bits = 8 * width;
  const std::uint64_t modulus = std::uint64_t{1} << bits;
  const std::uint64_t d = (static_cast<std::uint64_t>(now) - static_cast<std::uint64_t>(before)) & (modulus - 1);
  return d >= modulus / 2 ? static_cast<std::int64_t>(d) - static_cast<std::int64_t>(modulus)
                          : static_cast<std::int64_t>(d);
}

}  // namespace

So1Counts TickAccumulator::update(const So1RawTicks& raw) {
  if (!last_) {
    counts_ = {raw.left, raw.right};
  } else {
    counts_.left += wrap_delta(raw.left, last_->left, raw.width);
    counts_.right += wrap_delta(raw.right, last_->right, raw.width);
  }
  last_ = raw;
  return counts_;
}

void TickAccumulator::reset() {
  last_.reset();
  counts_ = {};
}

Expected<So1RawTicks> So1::decode_ticks(std::span<const std::uint8_t> data, unsigned width) {
  if (!valid_width(width)) return std::make_error_code(std::errc::invalid_argument);
  if (data.size() != 2 * width) return Outcome::bad_response;
  return So1RawTicks{width, load_signed(data.first(width), width), load_signed(data.subspan(width), width)};
}

Expected<So1RawTicks> So1::raw_ticks(unsigned width, const CallOptions& options) {
  if (!valid_width(width)) return std::make_error_code(std::errc::invalid_argument);
  auto r = call(so1::instr::kGetTicks, {static_cast<std::uint8_t>(width)}, options);
  if (!r) return r.error;
  return decode_ticks(r.data, width);
}

Expected<So1Counts> So1::counts(unsigned width, const CallOptions& options) {
  auto raw = raw_ticks(width, options);
  if (!raw) return raw.error();
  return accumulator_.update(*raw);
}

std::error_code So1::reset_ticks(const CallOptions& options) {
  auto ec = call_ack(so1::instr::kResetTicks, {}, options);
  if (!ec) accumulator_.reset();
  return ec;
}

}  // namespace advee::rs485
