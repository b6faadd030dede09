// SPDX-License-Identifier: GPL-2.0
#include "advee/rs485/devices/sd1.hpp"

#include "advee/byte_order.hpp"

namespace advee::rs485 {
namespace {

using Readings = std::vector<std::optional<double>>;

// n u8, then n x u16 cm. Returns the bytes consumed, 0 if malformed.
std::size_t parse_srf(std::span<const std::uint8_t> data, Readings& out) {
  if (data.empty()) return 0;
  const std::size_t n = data[0];
  const std::size_t size = 1 + 2 * n;
  if (data.size() < size) return 0;
  out.clear();
  for (std::size_t i = 0; i < n; ++i) {
    const auto raw = load_le<std::uint16_t>(data.subspan(1 + 2 * i, 2));
    out.push_back(raw == sd1::kSrfNoEcho ? std::nullopt : std::optional(raw * sd1::kMetresPerSrfUnit));
  }
  return size;
}

// m u8, then m x u8 mm/2.
std::size_t parse_ir(std::span<const std::uint8_t> data, Readings& out) {
  if (data.empty()) return 0;
  const std::size_t m = data[0];
  if (data.size() < 1 + m) return 0;
  out.clear();
  for (std::size_t i = 0; i < m; ++i) {
    const std::uint8_t raw = data[1 + i];
    out.push_back(raw == sd1::kIrOutOfRange ? std::nullopt : std::optional(raw * sd1::kMetresPerIrUnit));
  }
  return 1 + m;
}

}  // namespace

Expected<Readings> Sd1::decode_srf(std::span<const std::uint8_t> data) {
  Readings out;
  const auto used = parse_srf(data, out);
  if (!used || used != data.size()) return Outcome::bad_response;
  return out;
}

Expected<Readings> Sd1::decode_ir(std::span<const std::uint8_t> data) {
  Readings out;
  const auto used = parse_ir(data, out);
  if (!used || used != data.size()) return Outcome::bad_response;
  return out;
}

Expected<Sd1Distances> Sd1::decode_both(std::span<const std::uint8_t> data) {
  Sd1Distances d;
  const auto srf_used = parse_srf(data, d.srf_m);
  if (!srf_used) return Outcome::bad_response;
  const auto ir_used = parse_ir(data.subspan(srf_used), d.ir_m);
  if (!ir_used || srf_used + ir_used != data.size()) return Outcome::bad_response;
  return d;
}

Expected<PauseSources> Sd1::decode_pause_sources(std::span<const std::uint8_t> data) {
  if (data.size() != 1) return Outcome::bad_response;
  return PauseSources{data[0]};
}

Expected<Readings> Sd1::srf(const CallOptions& options) {
  auto r = call(sd1::instr::kGetSrf, {}, options);
  if (!r) return r.error;
  return decode_srf(r.data);
}

Expected<Readings> Sd1::ir(const CallOptions& options) {
  auto r = call(sd1::instr::kGetIr, {}, options);
  if (!r) return r.error;
  return decode_ir(r.data);
}

Expected<Sd1Distances> Sd1::distances(const CallOptions& options) {
  auto r = call(sd1::instr::kGetBoth, {}, options);
  if (!r) return r.error;
  return decode_both(r.data);
}

Expected<PauseSources> Sd1::pause_sources(const CallOptions& options) {
  auto r = call(sd1::instr::kGetPauseSource, {}, options);
  if (!r) return r.error;
  return decode_pause_sources(r.data);
}

std::error_code Sd1::clear_pause_sources(const CallOptions& options) {
  return call_ack(sd1::instr::kClearPauseSource, {}, options);
}

}  // namespace advee::rs485
