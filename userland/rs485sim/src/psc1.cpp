// SPDX-License-Identifier: GPL-2.0
#include <cmath>
#include <sstream>

#include "advee/rs485sim/devices.hpp"

namespace advee::rs485sim {

void Psc1::set_current(std::size_t ch, std::optional<double> amps) {
  if (ch >= kChannels) throw UsageError("channel " + std::to_string(ch) + " out of range 0..7");
  if (amps && *amps < 0) throw UsageError("current: negative");
  current_ma_[ch] = amps ? static_cast<std::uint16_t>(std::min(std::lround(*amps * 1000.0), 0xfffeL)) : 0xffff;
}

void Psc1::send_pause_event(bool engaged, std::uint8_t sources) {
  set_pause_state(engaged, sources);
  emit_event(kPauseEvent, {std::uint8_t(engaged), sources});
}

void Psc1::set_pause_period(std::chrono::milliseconds p, Clock::time_point now) {
  pause_periodic_ = {p, now + p};
}

void Psc1::set_power_period(std::chrono::milliseconds p, Clock::time_point now) {
  power_periodic_ = {p, now + p};
}

std::optional<Device::Result> Psc1::execute(std::uint8_t instr, std::span<const std::uint8_t> data,
                                            Clock::time_point) {
  Result r;
  switch (instr) {
    case kGetPwrStatus: r.data.push_back(status_); return r;
    case kSetPwrStatus:
      if (data.size() != 2) {
        r.flags = kRespDevErr;  // the board checks the request's length
        return r;
      }
      status_ = static_cast<std::uint8_t>((status_ & ~data[0]) | (data[1] & data[0]));
      r.data.push_back(status_);
      return r;
    case kGetCurrents:
      for (std::size_t ch = 0; ch < kChannels; ++ch) {
        // An unpowered channel draws nothing; a channel without a sensor says so.
        const bool on = status_ & (1u << ch);
        put_u16(r.data, current_ma_[ch] == 0xffff ? 0xffff : on ? current_ma_[ch] : 0);
      }
      return r;
    default: return std::nullopt;
  }
}

void Psc1::poll(Clock::time_point now) {
  for (auto* p : {&pause_periodic_, &power_periodic_}) {
    if (p->period.count() <= 0 || now < p->next) continue;
    if (p == &pause_periodic_)
      emit_event(kPauseEvent, {std::uint8_t(pause_engaged_), pause_sources_});
    else
      send_power_event();
    p->next += p->period;
    if (p->next < now) p->next = now + p->period;  // do not burst after a stall
  }
}

std::optional<Clock::time_point> Psc1::next_deadline() const {
  std::optional<Clock::time_point> t;
  for (const auto* p : {&pause_periodic_, &power_periodic_})
    if (p->period.count() > 0 && (!t || p->next < *t)) t = p->next;
  return t;
}

void Psc1::set(const std::string& key, const std::vector<std::string>& a) {
  const auto now = Clock::now();
  if (key == "status" && a.size() == 1) {
    set_status(static_cast<std::uint8_t>(parse_int(a[0], "status mask", 0, 0xff)));
  } else if (key == "current" && a.size() == 2) {
    const auto amps = a[1] == "none" ? std::nullopt : std::optional(parse_double(a[1], "current (A)"));
    if (a[0] == "all") {
      for (std::size_t ch = 0; ch < kChannels; ++ch) set_current(ch, amps);
    } else {
      set_current(static_cast<std::size_t>(parse_int(a[0], "channel", 0, 7)), amps);
    }
  } else if (key == "pause" && a.size() == 2) {
    set_pause_state(parse_int(a[0], "engaged", 0, 1) != 0,
                    static_cast<std::uint8_t>(parse_int(a[1], "sources", 0, 0xff)));
  } else if ((key == "pause-period" || key == "power-period") && a.size() == 1) {
    const std::chrono::milliseconds p(parse_int(a[0], "period (ms)", 0, 3600000));
    key == "pause-period" ? set_pause_period(p, now) : set_power_period(p, now);
  } else {
    throw UsageError("psc1: set status MASK, set current CH|all AMPS|none, set pause ENGAGED SOURCES, "
                     "set pause-period MS, set power-period MS");
  }
}

std::string Psc1::show(Clock::time_point) const {
  std::ostringstream o;
  o << "status=0x" << std::hex << unsigned(status_) << std::dec << " currents_ma";
  for (auto ma : current_ma_) o << ' ' << (ma == 0xffff ? std::string("none") : std::to_string(ma));
  o << " pause=" << pause_engaged_ << '/' << unsigned(pause_sources_);
  return o.str();
}

}  // namespace advee::rs485sim
