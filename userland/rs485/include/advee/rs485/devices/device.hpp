// SPDX-License-Identifier: GPL-2.0
// Base of the device drivers: one node at one address on a Transport, with
// the standard instructions of every device (firmware version, reset).
// Drivers do not own the transport; it must outlive them. The transport is
// thread-safe; a driver object is used by one thread at a time (So1 keeps
// its accumulated counts in the object).
#pragma once

#include <cstdint>
#include <span>
#include <system_error>
#include <vector>

#include "advee/rs485/error.hpp"
#include "advee/rs485/transport.hpp"

namespace advee::rs485 {

struct FirmwareVersion {
  std::uint8_t major = 0;
  std::uint8_t minor = 0;
  friend bool operator==(const FirmwareVersion&, const FirmwareVersion&) = default;
};

// GET_FW_VERSION response: exactly 2 bytes, else Outcome::bad_response.
Expected<FirmwareVersion> decode_firmware_version(std::span<const std::uint8_t> data);

// RESET to every device (address 0xFF): no response, OK once sent.
std::error_code broadcast_reset(Transport& transport);

class Device {
 public:
  Device(Transport& transport, std::uint8_t addr);
  virtual ~Device() = default;

  std::uint8_t address() const { return addr_; }
  Transport& transport() const { return *transport_; }

  Expected<FirmwareVersion> firmware_version(const CallOptions& options = {});
  // RESET: the node ACKs, then resets.
  std::error_code reset(const CallOptions& options = {});

 protected:
  // transact() to this node; the Result as is.
  Result call(std::uint8_t instr, std::vector<std::uint8_t> data = {}, const CallOptions& options = {});
  // transact() expecting an ACK with no data (data is ignored by the spec's ACK
  // instructions, so any data is accepted).
  std::error_code call_ack(std::uint8_t instr, std::vector<std::uint8_t> data = {},
                           const CallOptions& options = {});

 private:
  Transport* transport_;
  std::uint8_t addr_;
};

}  // namespace advee::rs485
