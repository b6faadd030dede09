// SPDX-License-Identifier: GPL-2.0
#include "advee/canopen/concise_dcf.hpp"

#include "advee/byte_order.hpp"

namespace advee::canopen {

namespace {

constexpr std::size_t kCountSize = 4;
constexpr std::size_t kEntryHeader = 2 + 1 + 4;  // index, sub-index, size

template <typename T>
void append_le(std::vector<std::uint8_t>& out, T v) {
  std::uint8_t b[sizeof(T)];
  store_le<T>(std::span(b), v);
  out.insert(out.end(), b, b + sizeof(T));
}

}  // namespace

std::vector<std::uint8_t> write_concise_dcf(const std::vector<SdoWrite>& writes) {
  std::vector<std::uint8_t> out;
  append_le<std::uint32_t>(out, static_cast<std::uint32_t>(writes.size()));
  for (const SdoWrite& w : writes) {
    append_le<std::uint16_t>(out, w.index);
    out.push_back(w.sub);
    append_le<std::uint32_t>(out, static_cast<std::uint32_t>(w.data.size()));
    out.insert(out.end(), w.data.begin(), w.data.end());
  }
  return out;
}

ConciseDcfResult parse_concise_dcf(std::span<const std::uint8_t> bytes) {
  ConciseDcfResult r;
  const auto fail = [&r](std::size_t offset, const std::string& what) {
    r.writes.clear();
    r.error = "byte " + std::to_string(offset) + ": " + what;
    return r;
  };
  if (bytes.size() < kCountSize)
    return fail(0, "a concise DCF starts with a 4-byte entry count; the file has " + std::to_string(bytes.size()) +
                       " bytes");
  const std::uint32_t count = load_le<std::uint32_t>(bytes.subspan(0, kCountSize));
  // Each entry takes at least its header: a count the file cannot hold is
  // refused before anything is reserved for it.
  if (count > (bytes.size() - kCountSize) / kEntryHeader)
    return fail(0, "entry count " + std::to_string(count) + " needs at least " +
                       std::to_string(kCountSize + std::uint64_t{count} * kEntryHeader) + " bytes; the file has " +
                       std::to_string(bytes.size()));
  r.writes.reserve(count);
  std::size_t at = kCountSize;
  for (std::uint32_t i = 0; i < count; ++i) {
    if (bytes.size() - at < kEntryHeader)
      return fail(at, "entry " + std::to_string(i + 1) + " of " + std::to_string(count) + " is cut short in its header");
    SdoWrite w;
    w.index = load_le<std::uint16_t>(bytes.subspan(at, 2));
    w.sub = bytes[at + 2];
    const std::uint32_t size = load_le<std::uint32_t>(bytes.subspan(at + 3, 4));
    at += kEntryHeader;
    if (bytes.size() - at < size)
      return fail(at, "entry " + std::to_string(i + 1) + " of " + std::to_string(count) + " declares " +
                          std::to_string(size) + " bytes of value; " + std::to_string(bytes.size() - at) + " are left");
    w.data.assign(bytes.begin() + static_cast<std::ptrdiff_t>(at), bytes.begin() + static_cast<std::ptrdiff_t>(at + size));
    at += size;
    r.writes.push_back(std::move(w));
  }
  if (at != bytes.size())
    return fail(at, std::to_string(bytes.size() - at) + " bytes after the last of " + std::to_string(count) + " entries");
  return r;
}

bool looks_like_concise_dcf(std::span<const std::uint8_t> bytes) {
  return bytes.size() >= kCountSize && bytes[kCountSize - 1] == 0;
}

}  // namespace advee::canopen
