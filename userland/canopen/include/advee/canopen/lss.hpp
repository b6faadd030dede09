// SPDX-License-Identifier: GPL-2.0
// CiA 305 Layer Setting Services: what master and slave share. All LSS
// frames are 8 bytes: the command specifier in byte 0, then the service's
// fields (little-endian 32-bit words at bytes 1..4). The master sends on
// 0x7E5, the slaves answer on 0x7E4.
#pragma once

#include <array>
#include <cstdint>
#include <optional>
#include <string>

namespace advee::canopen {

namespace cob {
inline constexpr std::uint32_t kLssMaster = 0x7E5;  // master -> slaves
inline constexpr std::uint32_t kLssSlave = 0x7E4;   // slave -> master
}  // namespace cob

// The LSS address: the four words of the node's identity object 0x1018.
struct LssAddress {
  std::array<std::uint32_t, 4> words{};  // vendor-ID, product code, revision, serial
  std::uint32_t vendor() const { return words[0]; }
  std::uint32_t product() const { return words[1]; }
  std::uint32_t revision() const { return words[2]; }
  std::uint32_t serial() const { return words[3]; }
  friend bool operator==(const LssAddress&, const LssAddress&) = default;
};

// "vendor 0x000000FB product 0x64200000 revision 0x00010000 serial 0x00000001"
std::string to_string(const LssAddress& a);

enum class LssMode : std::uint8_t { kWaiting = 0, kConfiguration = 1 };

// Node-ID of a node that has none: it answers LSS only (CiA 305).
inline constexpr std::uint8_t kLssUnconfigured = 0xFF;

namespace lss_cs {
inline constexpr std::uint8_t kSwitchGlobal = 0x04;
inline constexpr std::uint8_t kConfigureNodeId = 0x11;
inline constexpr std::uint8_t kConfigureBitTiming = 0x13;
inline constexpr std::uint8_t kActivateBitTiming = 0x15;
inline constexpr std::uint8_t kStore = 0x17;
inline constexpr std::uint8_t kSwitchSelectiveVendor = 0x40;  // + 0..3: product, revision, serial
inline constexpr std::uint8_t kSwitchSelectiveAnswer = 0x44;
inline constexpr std::uint8_t kIdentifySlave = 0x4F;  // answer to fastscan
inline constexpr std::uint8_t kIdentifyNonConfigured = 0x4C;
inline constexpr std::uint8_t kIdentifyNonConfiguredAnswer = 0x50;
inline constexpr std::uint8_t kFastscan = 0x51;
inline constexpr std::uint8_t kInquireVendor = 0x5A;  // + 0..3: product, revision, serial
inline constexpr std::uint8_t kInquireNodeId = 0x5E;
}  // namespace lss_cs

// Fastscan's bit-checked value that resets every non-configured slave's scan
// and makes it answer.
inline constexpr std::uint8_t kFastscanReset = 0x80;

// CiA 301 bit timing table (table selector 0): index -> kbit/s; index 5 is
// reserved (nullopt), 9 is automatic bit rate detection (0).
std::optional<unsigned> lss_bit_rate_kbit(std::uint8_t table_index);

}  // namespace advee::canopen
