// SPDX-License-Identifier: GPL-2.0
#include "advee/rs485/devices/device.hpp"

namespace advee::rs485 {

Expected<FirmwareVersion> decode_firmware_version(std::span<const std::uint8_t> data) {
  if (data.size() != 2) return Outcome::bad_response;
  return FirmwareVersion{data[0], data[1]};
}

std::error_code broadcast_reset(Transport& transport) {
  return transport.transact(Request(kBroadcast, standard_instr::kReset)).error;
}

Device::Device(Transport& transport, std::uint8_t addr) : transport_(&transport), addr_(addr) {}

Result Device::call(std::uint8_t instr, std::vector<std::uint8_t> data, const CallOptions& options) {
  return transport_->transact(Request(addr_, instr, std::move(data), options));
}

std::error_code Device::call_ack(std::uint8_t instr, std::vector<std::uint8_t> data, const CallOptions& options) {
  return call(instr, std::move(data), options).error;
}

Expected<FirmwareVersion> Device::firmware_version(const CallOptions& options) {
  auto r = call(standard_instr::kGetFirmwareVersion, {}, options);
  if (!r) return r.error;
  return decode_firmware_version(r.data);
}

std::error_code Device::reset(const CallOptions& options) {
  return call_ack(standard_instr::kReset, {}, options);
}

}  // namespace advee::rs485
