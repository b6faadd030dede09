// SPDX-License-Identifier: GPL-2.0
// Object dictionary of a node (the master's own, the simulated drive's): byte
// values keyed by (index, sub-index) with access rights, PDO mappability and per-index write
// validators that can refuse a write with an SDO abort code.
#pragma once

#include <cstdint>
#include <functional>
#include <map>
#include <optional>
#include <span>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "advee/byte_order.hpp"
#include "advee/canopen/sdo_abort.hpp"

namespace advee::canopen {

enum class Access { kReadOnly, kReadWrite, kWriteOnly };

struct OdEntry {
  std::vector<std::uint8_t> value;
  Access access = Access::kReadWrite;
  bool mappable = false;
  bool variable_size = false;  // strings/domains
  // What a device description (CiA 306 EDS/DCF, device_description.hpp) says
  // about the entry, kept as written so that a DCF written back says the same;
  // empty for entries added in code.
  std::string name;                           // ParameterName
  std::uint16_t data_type = 0;                // CiA 301 data type index (0x0007 UNSIGNED32); 0: not described
  std::string access_text;                    // AccessType: ro, wo, rw, rwr, rww, const
  std::string default_text;                   // DefaultValue ($NODEID expressions unevaluated)
  std::optional<std::string> parameter_text;  // DCF ParameterValue: the value to configure
  std::string low_limit, high_limit;
  friend bool operator==(const OdEntry&, const OdEntry&) = default;
};

// An object (index) as a device description declares it.
struct OdObject {
  std::string name;
  std::uint8_t object_type = 7;  // CiA 301: 7 VAR, 8 ARRAY, 9 RECORD, 2 DOMAIN
  friend bool operator==(const OdObject&, const OdObject&) = default;
};

class ObjectDictionary {
 public:
  // Returns kNone to accept, any other code to refuse.
  using Validator = std::function<SdoAbort(std::uint8_t sub, std::span<const std::uint8_t> data)>;
  using WriteHook = std::function<void(std::uint8_t sub)>;

  template <typename T>
  void add(std::uint16_t index, std::uint8_t sub, T value, Access a = Access::kReadWrite, bool mappable = false) {
    OdEntry e;
    e.value = to_bytes<T>(value);
    e.access = a;
    e.mappable = mappable;
    entries_[{index, sub}] = std::move(e);
  }
  void add_string(std::uint16_t index, std::uint8_t sub, std::string_view s, Access a = Access::kReadOnly);

  bool exists(std::uint16_t index, std::uint8_t sub) const { return entries_.count({index, sub}) != 0; }
  bool index_exists(std::uint16_t index) const;
  const OdEntry* find(std::uint16_t index, std::uint8_t sub) const;

  // SDO-side access: access rights, size and validators apply.
  SdoAbort read(std::uint16_t index, std::uint8_t sub, std::vector<std::uint8_t>& out) const;
  SdoAbort write(std::uint16_t index, std::uint8_t sub, std::span<const std::uint8_t> data);

  // Device-side access: no checks (RPDO reception, the drive's own state).
  template <typename T>
  T get(std::uint16_t index, std::uint8_t sub = 0) const {
    const OdEntry* e = find(index, sub);
    return e ? load_le<T>(e->value) : T{};
  }
  template <typename T>
  void set(std::uint16_t index, std::uint8_t sub, T value) {
    auto it = entries_.find({index, sub});
    if (it != entries_.end()) store_le<T>(it->second.value, value);
  }
  void set_raw(std::uint16_t index, std::uint8_t sub, std::uint64_t value);

  void set_validator(std::uint16_t index, Validator v) { validators_[index] = std::move(v); }
  void on_write(std::uint16_t index, WriteHook h) { hooks_[index] = std::move(h); }

  // Description data (device_description.hpp): entries added whole, the
  // objects they belong to, and both in (index, sub) order.
  void add_entry(std::uint16_t index, std::uint8_t sub, OdEntry e) { entries_[{index, sub}] = std::move(e); }
  void describe(std::uint16_t index, OdObject o) { objects_[index] = std::move(o); }
  const OdObject* object(std::uint16_t index) const;
  const std::map<std::pair<std::uint16_t, std::uint8_t>, OdEntry>& entries() const { return entries_; }
  const std::map<std::uint16_t, OdObject>& objects() const { return objects_; }

  // Restores [first, last] to the values of `defaults` (NMT resets).
  void restore(const ObjectDictionary& defaults, std::uint16_t first, std::uint16_t last);

 private:
  std::map<std::pair<std::uint16_t, std::uint8_t>, OdEntry> entries_;
  std::map<std::uint16_t, OdObject> objects_;
  std::map<std::uint16_t, Validator> validators_;
  std::map<std::uint16_t, WriteHook> hooks_;
};

}  // namespace advee::canopen
