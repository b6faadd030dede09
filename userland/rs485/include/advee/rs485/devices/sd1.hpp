// SPDX-License-Identifier: GPL-2.0
// BR-SD1 distance concentrator: 8 SRF-08 ultrasonic rangers, 2 Sharp
// GP2Y0A41 infrared sensors, and the PAUSE sources (bumpers, ground sensor).
//
// Units: distances in metres (double). A reading without a distance is
// std::nullopt: SRF 0xFFFF = no echo (nothing within range), IR 0 = out of
// range. A raw 0 from an SRF is a real 0.00 m reading (something touching).
#pragma once

#include <cstdint>
#include <optional>
#include <span>
#include <vector>

#include "advee/rs485/devices/device.hpp"

namespace advee::rs485 {

namespace sd1 {
namespace instr {
inline constexpr std::uint8_t kGetSrf = 0x01;          // -> n u8, n x u16 cm (0xFFFF no echo)
inline constexpr std::uint8_t kGetIr = 0x02;           // -> m u8, m x u8 mm/2 (0 out of range)
inline constexpr std::uint8_t kGetBoth = 0x10;         // -> SRF block then IR block
inline constexpr std::uint8_t kGetPauseSource = 0x20;  // -> u8 bit mask
inline constexpr std::uint8_t kClearPauseSource = 0x21;
}  // namespace instr
inline constexpr std::uint16_t kSrfNoEcho = 0xFFFF;
inline constexpr std::uint8_t kIrOutOfRange = 0;
inline constexpr double kMetresPerSrfUnit = 0.01;   // cm
inline constexpr double kMetresPerIrUnit = 0.002;   // mm/2
}  // namespace sd1

// Bits of GET_PAUSE_SRC.
struct PauseSources {
  static constexpr std::uint8_t kFrontBumper = 0x01;
  static constexpr std::uint8_t kRearBumper = 0x02;
  static constexpr std::uint8_t kGroundSensor = 0x04;
  static constexpr std::uint8_t kUltrasonicProximity = 0x08;

  std::uint8_t mask = 0;
  bool front_bumper() const { return mask & kFrontBumper; }
  bool rear_bumper() const { return mask & kRearBumper; }
  bool ground_sensor() const { return mask & kGroundSensor; }
  bool ultrasonic_proximity() const { return mask & kUltrasonicProximity; }
  bool any() const { return mask != 0; }
  friend bool operator==(const PauseSources&, const PauseSources&) = default;
};

struct Sd1Distances {
  std::vector<std::optional<double>> srf_m;  // metres; nullopt = no echo
  std::vector<std::optional<double>> ir_m;   // metres; nullopt = out of range
};

class Sd1 : public Device {
 public:
  using Device::Device;

  Expected<std::vector<std::optional<double>>> srf(const CallOptions& options = {});
  Expected<std::vector<std::optional<double>>> ir(const CallOptions& options = {});
  // SRF and IR in one transaction (GET_BOTH).
  Expected<Sd1Distances> distances(const CallOptions& options = {});
  Expected<PauseSources> pause_sources(const CallOptions& options = {});
  std::error_code clear_pause_sources(const CallOptions& options = {});

  // Decoders of the response data; Outcome::bad_response unless the data
  // has exactly the announced number of readings.
  static Expected<std::vector<std::optional<double>>> decode_srf(std::span<const std::uint8_t> data);
  static Expected<std::vector<std::optional<double>>> decode_ir(std::span<const std::uint8_t> data);
  static Expected<Sd1Distances> decode_both(std::span<const std::uint8_t> data);
  static Expected<PauseSources> decode_pause_sources(std::span<const std::uint8_t> data);
};

}  // namespace advee::rs485
