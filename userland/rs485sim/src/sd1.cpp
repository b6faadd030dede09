// SPDX-License-Identifier: GPL-2.0
#include <cmath>
#include <sstream>

#include "advee/rs485sim/devices.hpp"

namespace advee::rs485sim {

namespace {

std::optional<double> metres_arg(const std::string& s) {
  if (s == "none") return std::nullopt;
  const double m = parse_double(s, "distance (m)");
  if (m < 0) throw UsageError("distance (m): negative: " + s);
  return m;
}

}  // namespace

void Sd1::set_srf(std::size_t i, std::optional<double> m) {
  if (i >= kSrf) throw UsageError("srf index " + std::to_string(i) + " out of range 0..7");
  // u16 in cm; 0xffff is reserved for "no echo", so far readings saturate below it.
  srf_cm_[i] = m ? static_cast<std::uint16_t>(std::min(std::lround(*m * 100.0), 0xfffeL)) : 0xffff;
}

void Sd1::set_ir(std::size_t i, std::optional<double> m) {
  if (i >= kIr) throw UsageError("ir index " + std::to_string(i) + " out of range 0..1");
  // u8 in units of 2 mm; 0 = out of range, so is anything beyond 510 mm or under 1 mm.
  const long half_mm = m ? std::lround(*m * 500.0) : 0;
  ir_half_mm_[i] = half_mm >= 1 && half_mm <= 255 ? static_cast<std::uint8_t>(half_mm) : 0;
}

void Sd1::append_srf(std::vector<std::uint8_t>& v) const {
  v.push_back(kSrf);
  for (auto cm : srf_cm_) put_u16(v, cm);
}

void Sd1::append_ir(std::vector<std::uint8_t>& v) const {
  v.push_back(kIr);
  v.insert(v.end(), ir_half_mm_.begin(), ir_half_mm_.end());
}

std::optional<Device::Result> Sd1::execute(std::uint8_t instr, std::span<const std::uint8_t>,
                                           Clock::time_point) {
  Result r;
  switch (instr) {
    case kGetSrf: append_srf(r.data); return r;
    case kGetIr: append_ir(r.data); return r;
    case kGetBoth:
      append_srf(r.data);
      append_ir(r.data);
      return r;
    case kGetPauseSrc: r.data.push_back(pause_src_); return r;
    case kClearPauseSrc: pause_src_ = 0; return r;
    default: return std::nullopt;
  }
}

void Sd1::set(const std::string& key, const std::vector<std::string>& a) {
  if ((key == "srf" || key == "ir") && a.size() == 2) {
    const auto m = metres_arg(a[1]);
    const std::size_t n = key == "srf" ? kSrf : kIr;
    if (a[0] == "all") {
      for (std::size_t i = 0; i < n; ++i) key == "srf" ? set_srf(i, m) : set_ir(i, m);
    } else {
      const auto i = static_cast<std::size_t>(parse_int(a[0], "index", 0, long(n) - 1));
      key == "srf" ? set_srf(i, m) : set_ir(i, m);
    }
  } else if (key == "pause" && a.size() == 1) {
    raise_pause(static_cast<std::uint8_t>(parse_int(a[0], "pause sources", 0, 0xff)));
  } else {
    throw UsageError("sd1: set srf INDEX|all METRES|none, set ir INDEX|all METRES|none, "
                     "set pause MASK");
  }
}

std::string Sd1::show(Clock::time_point) const {
  std::ostringstream o;
  o << "srf_cm";
  for (auto cm : srf_cm_) o << ' ' << (cm == 0xffff ? std::string("none") : std::to_string(cm));
  o << " ir_2mm";
  for (auto v : ir_half_mm_) o << ' ' << unsigned(v);
  o << " pause_src=" << unsigned(pause_src_);
  return o.str();
}

}  // namespace advee::rs485sim
