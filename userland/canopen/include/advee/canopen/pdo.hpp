// SPDX-License-Identifier: GPL-2.0
// PDO mapping records (0x1600/0x1A00 + communication 0x1400/0x1800) and the
// frame codec built from a mapping read back from the device: objects packed
// LSB first in mapping order, at most 64 bits (canopen-notes.md §3.6).
#pragma once

#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "advee/canopen/frame.hpp"

namespace advee::canopen {

// "RPDO"/"TPDO" are named from the device's point of view: the master sends
// RPDOs and receives TPDOs.
enum class PdoKind { kRpdo, kTpdo };

struct PdoEntry {
  std::uint16_t index = 0;
  std::uint8_t sub = 0;
  std::uint8_t bits = 0;

  static PdoEntry from_raw(std::uint32_t raw) {
    return {static_cast<std::uint16_t>(raw >> 16), static_cast<std::uint8_t>(raw >> 8),
            static_cast<std::uint8_t>(raw)};
  }
  std::uint32_t raw() const {
    return (static_cast<std::uint32_t>(index) << 16) | (static_cast<std::uint32_t>(sub) << 8) | bits;
  }
  friend bool operator==(const PdoEntry&, const PdoEntry&) = default;
};

inline constexpr std::uint32_t kPdoCobInvalid = 0x80000000u;
inline constexpr std::uint32_t kPdoCobNoRtr = 0x40000000u;

struct PdoMapping {
  PdoKind kind = PdoKind::kRpdo;
  unsigned number = 1;  // 1-based: RPDO1 = 0x1400/0x1600
  std::uint32_t cob_id = kPdoCobInvalid;
  std::uint8_t transmission_type = 255;
  std::uint16_t inhibit_100us = 0;
  std::uint16_t event_timer_ms = 0;
  std::vector<PdoEntry> entries;

  bool enabled() const { return (cob_id & kPdoCobInvalid) == 0; }
  std::uint32_t can_id() const { return cob_id & 0x7FF; }
  unsigned total_bits() const;
  bool maps(std::uint16_t index, std::uint8_t sub) const;
};

std::uint16_t pdo_comm_index(PdoKind kind, unsigned number);
std::uint16_t pdo_map_index(PdoKind kind, unsigned number);
// The predefined connection set COB-ID of PDO 1..4 of a node.
std::uint32_t default_pdo_cob_id(PdoKind kind, unsigned number, std::uint8_t node);
// "RPDO4 0x505: 6040:00/16 60FF:00/32"
std::string to_string(const PdoMapping& m);

class PdoCodec {
 public:
  // nullopt (with the reason in *why) if the mapping exceeds 64 bits or is disabled.
  static std::optional<PdoCodec> build(const PdoMapping& m, std::string* why = nullptr);

  std::uint32_t can_id() const { return can_id_; }
  std::uint8_t length() const { return length_; }
  bool contains(std::uint16_t index, std::uint8_t sub) const { return find(index, sub) != nullptr; }

  CanFrame blank() const;
  // False if the object is not mapped. Extra high bits of value are dropped.
  bool set(CanFrame& f, std::uint16_t index, std::uint8_t sub, std::uint64_t value) const;
  // nullopt if the object is not mapped or the frame is shorter than the mapping.
  std::optional<std::uint64_t> get_unsigned(const CanFrame& f, std::uint16_t index, std::uint8_t sub) const;
  std::optional<std::int64_t> get_signed(const CanFrame& f, std::uint16_t index, std::uint8_t sub) const;

 private:
  struct Field {
    PdoEntry entry;
    unsigned offset = 0;  // bit offset in the payload
  };
  const Field* find(std::uint16_t index, std::uint8_t sub) const;

  std::uint32_t can_id_ = 0;
  std::uint8_t length_ = 0;
  std::vector<Field> fields_;
};

}  // namespace advee::canopen
