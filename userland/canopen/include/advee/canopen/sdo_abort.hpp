// SPDX-License-Identifier: GPL-2.0
// SDO abort codes of CiA 301 (spec: canopen-notes.md §3.4) as a typed enum,
// plus a std::error_category so results compose with std::error_code.
#pragma once

#include <cstdint>
#include <string_view>
#include <system_error>

namespace advee::canopen {

enum class SdoAbort : std::uint32_t {
  kNone = 0,
  kToggleBit = 0x05030000,
  kTimeout = 0x05040000,
  kUnknownCommand = 0x05040001,
  kInvalidBlockSize = 0x05040002,
  kInvalidSequence = 0x05040003,
  kCrcError = 0x05040004,
  kOutOfMemory = 0x05040005,
  kUnsupportedAccess = 0x06010000,
  kWriteOnly = 0x06010001,
  kReadOnly = 0x06010002,
  kNoObject = 0x06020000,
  kNotMappable = 0x06040041,
  kPdoTooLong = 0x06040042,
  kParamIncompatible = 0x06040043,
  kInternalIncompatible = 0x06040047,
  kHardware = 0x06060000,
  kTypeMismatch = 0x06070010,
  kTooLong = 0x06070012,
  kTooShort = 0x06070013,
  kNoSubindex = 0x06090011,
  kInvalidValue = 0x06090030,
  kValueTooHigh = 0x06090031,
  kValueTooLow = 0x06090032,
  kMaxLessThanMin = 0x06090036,
  kNoResource = 0x060A0023,
  kGeneral = 0x08000000,
  kDataStore = 0x08000020,
  kDataStoreLocal = 0x08000021,
  kDataStoreState = 0x08000022,
  kNoDictionary = 0x08000023,
  kNoData = 0x08000024,
};

// CiA 301 meaning of a code ("unknown abort code" for vendor codes).
std::string_view describe(SdoAbort code);

const std::error_category& sdo_category();
inline std::error_code make_error_code(SdoAbort a) {
  return {static_cast<int>(static_cast<std::uint32_t>(a)), sdo_category()};
}

}  // namespace advee::canopen

template <>
struct std::is_error_code_enum<advee::canopen::SdoAbort> : std::true_type {};
