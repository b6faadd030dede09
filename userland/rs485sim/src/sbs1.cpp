// SPDX-License-Identifier: GPL-2.0
#include <algorithm>
#include <cmath>
#include <sstream>

#include "advee/rs485sim/devices.hpp"

namespace advee::rs485sim {

void Sbs1::set_beacon(std::uint8_t id, std::optional<Sighting> s) {
  if (s)
    visible_[id] = *s;
  else
    visible_.erase(id);
}

std::optional<Device::Result> Sbs1::execute(std::uint8_t instr, std::span<const std::uint8_t> data,
                                            Clock::time_point) {
  Result r;
  switch (instr) {
    case kSetBeaconIds: ids_.assign(data.begin(), data.end()); return r;
    case kGetBeaconData: {
      r.data.push_back(0);
      for (auto id : ids_) {
        const auto it = visible_.find(id);
        if (it == visible_.end()) continue;
        // 0.01 degree, 0..35999.
        long centi = std::lround(it->second.bearing_deg * 100.0) % 36000;
        if (centi < 0) centi += 36000;
        r.data.push_back(id);
        put_u16(r.data, static_cast<std::uint16_t>(centi));
        r.data.push_back(it->second.quality);
        ++r.data[0];
      }
      return r;
    }
    case kGetDebugData: {
      // Opaque to the master; the simulator reports its model and the ids set.
      static constexpr char kTag[] = "sbs1-sim";
      r.data.assign(kTag, kTag + sizeof(kTag) - 1);
      r.data.push_back(static_cast<std::uint8_t>(ids_.size()));
      return r;
    }
    default: return std::nullopt;
  }
}

void Sbs1::set(const std::string& key, const std::vector<std::string>& a) {
  if (key == "beacon" && a.size() == 2 && a[1] == "none") {
    set_beacon(static_cast<std::uint8_t>(parse_int(a[0], "beacon id", 0, 255)), std::nullopt);
  } else if (key == "beacon" && a.size() == 3) {
    set_beacon(static_cast<std::uint8_t>(parse_int(a[0], "beacon id", 0, 255)),
               Sighting{parse_double(a[1], "bearing (degrees)"),
                        static_cast<std::uint8_t>(parse_int(a[2], "quality", 0, 255))});
  } else if (key == "ids") {
    std::vector<std::uint8_t> ids;
    for (const auto& s : a) ids.push_back(static_cast<std::uint8_t>(parse_int(s, "beacon id", 0, 255)));
    set_ids(std::move(ids));
  } else {
    throw UsageError("sbs1: set beacon ID DEGREES QUALITY, set beacon ID none, set ids ID...");
  }
}

std::string Sbs1::show(Clock::time_point) const {
  std::ostringstream o;
  o << "ids";
  for (auto id : ids_) o << ' ' << unsigned(id);
  o << " visible";
  for (const auto& [id, s] : visible_) o << ' ' << unsigned(id) << ':' << s.bearing_deg << '/' << unsigned(s.quality);
  return o.str();
}

}  // namespace advee::rs485sim
