// SPDX-License-Identifier: GPL-2.0
#include "advee/canopen/object_dictionary.hpp"

namespace advee::canopen {

void ObjectDictionary::add_string(std::uint16_t index, std::uint8_t sub, std::string_view s, Access a) {
  OdEntry e;
  e.value.assign(s.begin(), s.end());
  e.access = a;
  e.variable_size = true;
  entries_[{index, sub}] = std::move(e);
}

bool ObjectDictionary::index_exists(std::uint16_t index) const {
  auto it = entries_.lower_bound({index, 0});
  return it != entries_.end() && it->first.first == index;
}

const OdObject* ObjectDictionary::object(std::uint16_t index) const {
  auto it = objects_.find(index);
  return it == objects_.end() ? nullptr : &it->second;
}

const OdEntry* ObjectDictionary::find(std::uint16_t index, std::uint8_t sub) const {
  auto it = entries_.find({index, sub});
  return it == entries_.end() ? nullptr : &it->second;
}

SdoAbort ObjectDictionary::read(std::uint16_t index, std::uint8_t sub, std::vector<std::uint8_t>& out) const {
  const OdEntry* e = find(index, sub);
  if (!e) return index_exists(index) ? SdoAbort::kNoSubindex : SdoAbort::kNoObject;
  if (e->access == Access::kWriteOnly) return SdoAbort::kWriteOnly;
  out = e->value;
  return SdoAbort::kNone;
}

SdoAbort ObjectDictionary::write(std::uint16_t index, std::uint8_t sub, std::span<const std::uint8_t> data) {
  auto it = entries_.find({index, sub});
  if (it == entries_.end()) return index_exists(index) ? SdoAbort::kNoSubindex : SdoAbort::kNoObject;
  OdEntry& e = it->second;
  if (e.access == Access::kReadOnly) return SdoAbort::kReadOnly;
  if (!e.variable_size) {
    if (data.size() > e.value.size()) return SdoAbort::kTooLong;
    if (data.size() < e.value.size()) return SdoAbort::kTooShort;
  }
  if (auto v = validators_.find(index); v != validators_.end()) {
    const SdoAbort a = v->second(sub, data);
    if (a != SdoAbort::kNone) return a;
  }
  e.value.assign(data.begin(), data.end());
  if (auto h = hooks_.find(index); h != hooks_.end()) h->second(sub);
  return SdoAbort::kNone;
}

void ObjectDictionary::set_raw(std::uint16_t index, std::uint8_t sub, std::uint64_t value) {
  auto it = entries_.find({index, sub});
  if (it == entries_.end()) return;
  auto& v = it->second.value;
  for (std::size_t i = 0; i < v.size() && i < 8; ++i) v[i] = static_cast<std::uint8_t>(value >> (8 * i));
}

void ObjectDictionary::restore(const ObjectDictionary& defaults, std::uint16_t first, std::uint16_t last) {
  for (auto& [key, e] : entries_)
    if (key.first >= first && key.first <= last)
      if (const OdEntry* d = defaults.find(key.first, key.second)) e.value = d->value;
}

}  // namespace advee::canopen
