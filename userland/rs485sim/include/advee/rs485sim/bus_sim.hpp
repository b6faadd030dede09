// SPDX-License-Identifier: GPL-2.0
// One simulated bus: the receive state machine shared by the devices on it,
// dispatch by address, and the frames to transmit with the time each is due.
// Pure logic (no file descriptors), driven by the program's event loop or by
// the unit tests with words in memory.
#pragma once

#include <functional>
#include <map>
#include <memory>
#include <random>
#include <string>
#include <vector>

#include "advee/rs485sim/device.hpp"
#include "advee/rs485sim/wire_frame.hpp"

namespace advee::rs485sim {

struct Transmission {
  Clock::time_point due;
  std::vector<std::uint16_t> words;
};

class BusSim {
 public:
  using Logger = std::function<void(const std::string&)>;

  // full_duplex: spontaneous event frames may be sent (the EIA-422 link).
  BusSim(std::string name, bool full_duplex, std::uint32_t seed = 1);
  BusSim(const BusSim&) = delete;
  BusSim& operator=(const BusSim&) = delete;

  const std::string& name() const { return name_; }
  bool full_duplex() const { return full_duplex_; }

  // Throws UsageError for address 0xff or an address already taken.
  Device& add(std::unique_ptr<Device> dev);
  Device* find(std::uint8_t addr) const;
  const std::vector<std::unique_ptr<Device>>& devices() const { return devices_; }

  // Words read from the wire (what the master sent).
  void feed(std::span<const std::uint16_t> words, Clock::time_point now);
  // Periodic device events that are due.
  void poll(Clock::time_point now);
  // Earliest time something is due (a transmission or a periodic event).
  std::optional<Clock::time_point> next_deadline() const;
  // Transmissions due at `now`, oldest first, removed from the queue.
  std::vector<Transmission> take_due(Clock::time_point now);
  std::size_t pending() const { return queue_.size(); }

  const ReceiverStats& receiver_stats() const { return rx_.stats(); }
  void set_logger(Logger l) { log_ = std::move(l); }

 private:
  void on_frame(const Frame& f);
  void on_event(const Device& d, const Frame& f);

  std::string name_;
  bool full_duplex_;
  std::mt19937 rng_;
  std::vector<std::unique_ptr<Device>> devices_;
  Receiver rx_;
  Clock::time_point now_{};
  std::multimap<Clock::time_point, std::vector<std::uint16_t>> queue_;
  Logger log_;
};

}  // namespace advee::rs485sim
