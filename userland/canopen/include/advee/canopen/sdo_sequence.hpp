// SPDX-License-Identifier: GPL-2.0
// A list of SDO downloads run one after the other, stopping at the first
// failure: boot-time configuration and the PDO remap procedure.
#pragma once

#include <cstdint>
#include <functional>
#include <string>
#include <system_error>
#include <vector>

#include "advee/byte_order.hpp"
#include "advee/canopen/sdo_client.hpp"

namespace advee::canopen {

struct SdoWrite {
  std::uint16_t index = 0;
  std::uint8_t sub = 0;
  std::vector<std::uint8_t> data;

  template <typename T>
  static SdoWrite of(std::uint16_t index, std::uint8_t sub, T value) {
    return {index, sub, to_bytes<T>(value)};
  }
  friend bool operator==(const SdoWrite&, const SdoWrite&) = default;
};

struct SdoSequenceResult {
  std::error_code error;   // empty on success
  std::size_t failed_step = 0;  // index into the list when error is set
  SdoWrite failed;
};

void run_sdo_writes(SdoClient& sdo, std::vector<SdoWrite> writes,
                    std::function<void(const SdoSequenceResult&)> done);

}  // namespace advee::canopen
