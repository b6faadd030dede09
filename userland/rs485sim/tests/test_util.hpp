// SPDX-License-Identifier: GPL-2.0
// Helpers of the simulator's unit tests: requests as wire words, the one
// response a bus has queued, decoded back into a frame.
#pragma once

#include <gtest/gtest.h>

#include <optional>

#include "advee/rs485sim/bus_sim.hpp"

namespace advee::rs485sim::test {

inline const Clock::time_point kT0 = Clock::time_point(std::chrono::seconds(1000));

// Decodes wire words (one frame); crc_ok tells whether the CRC matched.
struct Decoded {
  Frame frame;
  bool crc_ok = false;
};

inline std::optional<Decoded> decode(const std::vector<std::uint16_t>& w) {
  std::optional<Decoded> out;
  Receiver rx([&](const Frame& f) { out = Decoded{f, true}; });
  rx.feed(w);
  if (!out && rx.stats().crc_errors == 1) {
    // Rebuild the frame without its CRC to show what was sent.
    Frame f{static_cast<std::uint8_t>(w.at(0) & 0xff), static_cast<std::uint8_t>(w.at(1)),
            static_cast<std::uint8_t>(w.at(2)), {}};
    for (std::size_t i = 4; i + 1 < w.size(); ++i) f.data.push_back(static_cast<std::uint8_t>(w[i]));
    out = Decoded{f, false};
  }
  return out;
}

// Sends a request on the bus and returns everything transmitted within 1 s.
inline std::vector<Decoded> transact(BusSim& bus, const Frame& req, std::uint8_t crc_xor = 0,
                                     Clock::time_point now = kT0) {
  bus.feed(encode_words(req, crc_xor), now);
  std::vector<Decoded> out;
  for (const auto& tx : bus.take_due(now + std::chrono::seconds(1))) {
    auto d = decode(tx.words);
    EXPECT_TRUE(d.has_value());
    if (d) out.push_back(*d);
  }
  return out;
}

inline std::vector<std::uint8_t> bytes(std::initializer_list<int> l) {
  std::vector<std::uint8_t> v;
  for (int x : l) v.push_back(static_cast<std::uint8_t>(x));
  return v;
}

}  // namespace advee::rs485sim::test
