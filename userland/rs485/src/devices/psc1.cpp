// SPDX-License-Identifier: GPL-2.0
#include "advee/rs485/devices/psc1.hpp"

#include "advee/byte_order.hpp"

namespace advee::rs485 {

Expected<std::uint8_t> Psc1::decode_power_status(std::span<const std::uint8_t> data) {
  if (data.size() != 1) return Outcome::bad_response;
  return data[0];
}

Expected<Psc1Currents> Psc1::decode_currents(std::span<const std::uint8_t> data) {
  if (data.size() != 2 * psc1::kChannels) return Outcome::bad_response;
  Psc1Currents out;
  for (std::size_t i = 0; i < psc1::kChannels; ++i) {
    const auto raw = load_le<std::uint16_t>(data.subspan(2 * i, 2));
    out[i] = raw == psc1::kNoSensor ? std::nullopt : std::optional(raw * psc1::kAmperesPerUnit);
  }
  return out;
}

Expected<Psc1Event> Psc1::decode_event(const Frame& frame) {
  if (!frame.is_event()) return Outcome::bad_response;
  if (frame.instr == psc1::instr::kPauseEvent && frame.data.size() == 2 && frame.data[0] <= 1)
    return Psc1Event{PauseEvent{frame.data[0] == 1, frame.data[1]}};
  if (frame.instr == psc1::instr::kPowerEvent && frame.data.size() == 1)
    return Psc1Event{PowerEvent{frame.data[0]}};
  return Outcome::bad_response;
}

Expected<std::uint8_t> Psc1::power_status(const CallOptions& options) {
  auto r = call(psc1::instr::kGetPowerStatus, {}, options);
  if (!r) return r.error;
  return decode_power_status(r.data);
}

Expected<std::uint8_t> Psc1::set_power_status(std::uint8_t mask, std::uint8_t values, const CallOptions& options) {
  auto r = call(psc1::instr::kSetPowerStatus, {mask, values}, options);
  if (!r) return r.error;
  return decode_power_status(r.data);
}

Expected<Psc1Currents> Psc1::currents(const CallOptions& options) {
  auto r = call(psc1::instr::kGetCurrents, {}, options);
  if (!r) return r.error;
  return decode_currents(r.data);
}

Subscription Psc1::on_pause(std::function<void(const PauseEvent&)> handler) {
  const auto addr = address();
  return transport().subscribe([addr, handler = std::move(handler)](const Frame& f) {
    if (f.addr != addr) return;
    if (auto ev = decode_event(f); ev && std::holds_alternative<PauseEvent>(*ev)) handler(std::get<PauseEvent>(*ev));
  });
}

Subscription Psc1::on_power(std::function<void(const PowerEvent&)> handler) {
  const auto addr = address();
  return transport().subscribe([addr, handler = std::move(handler)](const Frame& f) {
    if (f.addr != addr) return;
    if (auto ev = decode_event(f); ev && std::holds_alternative<PowerEvent>(*ev)) handler(std::get<PowerEvent>(*ev));
  });
}

}  // namespace advee::rs485
