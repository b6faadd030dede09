// SPDX-License-Identifier: GPL-2.0
#include "advee/canopen/sdo_abort.hpp"

#include <cstdio>
#include <string>

namespace advee::canopen {

std::string_view describe(SdoAbort code) {
  switch (code) {
    case SdoAbort::kNone: return "no error";
    case SdoAbort::kToggleBit: return "toggle bit not alternated";
    case SdoAbort::kTimeout: return "SDO protocol timed out";
    case SdoAbort::kUnknownCommand: return "command specifier not valid or unknown";
    case SdoAbort::kInvalidBlockSize: return "invalid block size";
    case SdoAbort::kInvalidSequence: return "invalid sequence number";
    case SdoAbort::kCrcError: return "CRC error";
    case SdoAbort::kOutOfMemory: return "out of memory";
    case SdoAbort::kUnsupportedAccess: return "unsupported access to an object";
    case SdoAbort::kWriteOnly: return "attempt to read a write-only object";
    case SdoAbort::kReadOnly: return "attempt to write a read-only object";
    case SdoAbort::kNoObject: return "object does not exist in the object dictionary";
    case SdoAbort::kNotMappable: return "object cannot be mapped to the PDO";
    case SdoAbort::kPdoTooLong: return "mapped objects would exceed the PDO length";
    case SdoAbort::kParamIncompatible: return "general parameter incompatibility";
    case SdoAbort::kInternalIncompatible: return "general internal incompatibility in the device";
    case SdoAbort::kHardware: return "access failed due to a hardware error";
    case SdoAbort::kTypeMismatch: return "data type does not match, length of service parameter does not match";
    case SdoAbort::kTooLong: return "data type does not match, length of service parameter too high";
    case SdoAbort::kTooShort: return "data type does not match, length of service parameter too low";
    case SdoAbort::kNoSubindex: return "sub-index does not exist";
    case SdoAbort::kInvalidValue: return "invalid value for parameter";
    case SdoAbort::kValueTooHigh: return "value of parameter written too high";
    case SdoAbort::kValueTooLow: return "value of parameter written too low";
    case SdoAbort::kMaxLessThanMin: return "maximum value is less than minimum value";
    case SdoAbort::kNoResource: return "resource not available: SDO connection";
    case SdoAbort::kGeneral: return "general error";
    case SdoAbort::kDataStore: return "data cannot be transferred or stored to the application";
    case SdoAbort::kDataStoreLocal:
      return "data cannot be transferred or stored to the application because of local control";
    case SdoAbort::kDataStoreState:
      return "data cannot be transferred or stored to the application because of the present device state";
    case SdoAbort::kNoDictionary: return "object dictionary dynamic generation failed or no object dictionary";
    case SdoAbort::kNoData: return "no data available";
  }
  return "unknown abort code";
}

namespace {
class SdoCategory final : public std::error_category {
 public:
  const char* name() const noexcept override { return "canopen-sdo"; }
  std::string message(int ev) const override {
    char hex[16];
    std::snprintf(hex, sizeof hex, "0x%08X", static_cast<unsigned>(ev));
    return std::string(describe(static_cast<SdoAbort>(static_cast<std::uint32_t>(ev)))) + " (" + hex + ")";
  }
};
}  // namespace

const std::error_category& sdo_category() {
  static const SdoCategory cat;
  return cat;
}

}  // namespace advee::canopen
