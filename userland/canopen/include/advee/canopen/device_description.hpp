// SPDX-License-Identifier: GPL-2.0
// Device descriptions (CiA 306): EDS and DCF files, INI text, read into the
// ObjectDictionary model (each entry keeps ParameterName, DataType,
// AccessType, DefaultValue and the DCF's ParameterValue as written, its value
// evaluated for one node-ID), and a DCF written back from that model.
// docs/canopen.md "Device descriptions" lists what is read and what is not.
#pragma once

#include <cstdint>
#include <optional>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "advee/canopen/object_dictionary.hpp"

namespace advee::canopen {

// One problem in a description file: where, and what was expected there.
struct DescriptionError {
  std::string file;
  unsigned line = 0;  // 1-based; 0: the file as a whole (cannot open, empty)
  std::string message;
  std::string text() const;  // "file:line: message"
};

struct DeviceDescription {
  // A section's keys and values as written, in file order.
  using Section = std::vector<std::pair<std::string, std::string>>;
  Section file_info;      // [FileInfo]
  Section device_info;    // [DeviceInfo]
  Section dummy_usage;    // [DummyUsage]
  Section commissioning;  // [DeviceComissioning] (CiA 306 spells it so): a DCF has it
  ObjectDictionary od;
  std::uint8_t node_id = 0;  // what $NODEID evaluated to (0: none known, an EDS)

  bool is_dcf() const { return !commissioning.empty(); }
  // A key's value in a section (keys compare without case).
  static std::optional<std::string> value(const Section& s, std::string_view key);
};

// The same model: sections, objects and entries (values and the texts they
// came from); validators and hooks are not compared.
bool same_model(const DeviceDescription& a, const DeviceDescription& b);

struct DescriptionResult {
  std::optional<DeviceDescription> description;  // set when errors is empty
  std::vector<DescriptionError> errors;
};

// node_id evaluates $NODEID; without it, a DCF's [DeviceComissioning] NodeID
// does, and an EDS without either evaluates $NODEID as 0. Never throws on bad
// input: every problem found is in errors (at most kMaxDescriptionErrors).
inline constexpr std::size_t kMaxDescriptionErrors = 50;
DescriptionResult parse_device_description(std::string_view text, std::string_view file_name,
                                           std::optional<std::uint8_t> node_id = std::nullopt);
DescriptionResult load_device_description(const std::string& path, std::optional<std::uint8_t> node_id = std::nullopt);

// The model as a DCF: the info sections, the three object lists (mandatory
// 0x1000, 0x1001, 0x1018; manufacturer 0x2000-0x5FFF; optional the rest),
// one section per object and sub-object, CompactSubObj expanded.
std::string write_dcf(const DeviceDescription& d);

// CiA 301 data type name ("UNSIGNED32") or "" when unknown.
std::string_view data_type_name(std::uint16_t data_type);

}  // namespace advee::canopen
