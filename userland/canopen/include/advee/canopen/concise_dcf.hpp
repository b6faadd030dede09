// SPDX-License-Identifier: GPL-2.0
// Concise DCF (CiA 302-3, the format of object 0x1F22): the binary list of
// SDO downloads that configure a node, as a manager keeps it for each node
// instead of the DCF text. Little-endian: UNSIGNED32 number of entries, then
// per entry UNSIGNED16 index, UNSIGNED8 sub-index, UNSIGNED32 size in bytes
// and the value. It carries no identity: a boot from it checks nothing.
#pragma once

#include <cstdint>
#include <span>
#include <string>
#include <vector>

#include "advee/canopen/sdo_sequence.hpp"

namespace advee::canopen {

std::vector<std::uint8_t> write_concise_dcf(const std::vector<SdoWrite>& writes);

struct ConciseDcfResult {
  std::vector<SdoWrite> writes;
  std::string error;  // empty on success, else what is wrong and at which byte offset
  bool ok() const { return error.empty(); }
};

// Never throws on bad input: a short file, an entry cut short, a count that
// does not match the entries and bytes after the last entry are errors.
ConciseDcfResult parse_concise_dcf(std::span<const std::uint8_t> bytes);

// Whether a file's first bytes are a concise DCF's rather than an EDS's or
// DCF's text: the entry count's high byte is 0 (fewer than 2^24 entries),
// and a CiA 306 text file has no NUL byte.
bool looks_like_concise_dcf(std::span<const std::uint8_t> bytes);

}  // namespace advee::canopen
