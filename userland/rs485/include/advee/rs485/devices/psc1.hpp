// SPDX-License-Identifier: GPL-2.0
// BR-PSC1 eight-channel power controller on the full-duplex EIA-422 link:
// channel power status, channel currents, and the PAUSE and POWER events
// the board sends on its own (delivered to callbacks on the transport's
// event thread).
#pragma once

#include <array>
#include <cstdint>
#include <functional>
#include <optional>
#include <span>
#include <variant>

#include "advee/rs485/devices/device.hpp"

namespace advee::rs485 {

namespace psc1 {
namespace instr {
inline constexpr std::uint8_t kGetPowerStatus = 0x01;  // -> u8 mask (bit i = channel i on)
inline constexpr std::uint8_t kSetPowerStatus = 0x02;  // mask u8, values u8 -> new status u8
inline constexpr std::uint8_t kGetCurrents = 0x03;     // -> 8 x u16 mA (0xFFFF = no sensor)
inline constexpr std::uint8_t kPauseEvent = 0x40;      // event: engaged u8 (0/1), sources u8
inline constexpr std::uint8_t kPowerEvent = 0x41;      // event: new status u8
}  // namespace instr
inline constexpr std::size_t kChannels = 8;
inline constexpr std::uint16_t kNoSensor = 0xFFFF;
inline constexpr double kAmperesPerUnit = 0.001;  // mA
}  // namespace psc1

// Channel currents in amperes; nullopt = the channel has no sensor.
using Psc1Currents = std::array<std::optional<double>, psc1::kChannels>;

struct PauseEvent {
  bool engaged = false;
  std::uint8_t sources = 0;  // same bits as PauseSources (sd1.hpp)
  friend bool operator==(const PauseEvent&, const PauseEvent&) = default;
};

struct PowerEvent {
  std::uint8_t status = 0;  // bit i = channel i powered
  friend bool operator==(const PowerEvent&, const PowerEvent&) = default;
};

using Psc1Event = std::variant<PauseEvent, PowerEvent>;

class Psc1 : public Device {
 public:
  using Device::Device;

  Expected<std::uint8_t> power_status(const CallOptions& options = {});
  // Channels whose bit is set in `mask` get the corresponding bit of `values`;
  // returns the new status the board reports.
  Expected<std::uint8_t> set_power_status(std::uint8_t mask, std::uint8_t values,
                                          const CallOptions& options = {});
  Expected<Psc1Currents> currents(const CallOptions& options = {});

  // Events from this board's address (FLAGS with EVENT). Malformed event
  // frames are not delivered (see decode_event). The Subscription must not
  // outlive the transport.
  Subscription on_pause(std::function<void(const PauseEvent&)> handler);
  Subscription on_power(std::function<void(const PowerEvent&)> handler);

  static Expected<std::uint8_t> decode_power_status(std::span<const std::uint8_t> data);
  static Expected<Psc1Currents> decode_currents(std::span<const std::uint8_t> data);
  // An event frame of a PSC1 (any address): PAUSE needs exactly 2 data bytes
  // with engaged 0 or 1, POWER exactly 1; anything else (also a frame without
  // the EVENT flag or another instruction) is Outcome::bad_response.
  static Expected<Psc1Event> decode_event(const Frame& frame);
};

}  // namespace advee::rs485
