// SPDX-License-Identifier: GPL-2.0
// Reading a device's PDO configuration back over SDO, and the CiA 301 safe
// remap procedure (canopen-notes.md §3.6). Never assume a vendor default.
#pragma once

#include <functional>
#include <system_error>
#include <vector>

#include "advee/canopen/pdo.hpp"
#include "advee/canopen/sdo_client.hpp"
#include "advee/canopen/sdo_sequence.hpp"

namespace advee::canopen {

// Reads COB-ID (sub1), transmission type (sub2), for TPDOs inhibit (sub3) and
// event timer (sub5) when present, mapping sub0 and each entry.
void read_pdo_mapping(SdoClient& sdo, PdoKind kind, unsigned number,
                      std::function<void(std::error_code, const PdoMapping&)> done);

// The SDO writes of the safe remap: invalidate COB-ID, sub0 = 0, entries,
// sub0 = n, communication parameters, COB-ID valid (or left invalid if
// `wanted` is disabled). The node should be pre-operational.
std::vector<SdoWrite> pdo_remap_writes(const PdoMapping& wanted);

// Only the COB-ID write needed to switch an otherwise correct PDO on or off.
SdoWrite pdo_enable_write(const PdoMapping& m, bool enable);

}  // namespace advee::canopen
