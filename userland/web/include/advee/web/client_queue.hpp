// SPDX-License-Identifier: GPL-2.0
// What one browser has not been sent yet. A slow client must not make the
// bridge grow without bound: a newer message replaces the pending one with
// the same key (replace_key(): channel, plus module for shared channels), and
// each replacement counts as a drop. The number of keys is capped as well
// (oldest key out, counted) against a flood of distinct module names.
#pragma once

#include <cstddef>
#include <cstdint>
#include <list>
#include <string>
#include <unordered_map>
#include <vector>

namespace advee::web {

class ClientQueue {
 public:
  explicit ClientQueue(std::size_t max_keys = 256) : max_keys_(max_keys) {}

  // Queues `payload` under `key`; replaces (and counts as dropped) an unsent
  // one of the same key, which keeps its place in the sending order.
  void push(const std::string& key, std::string payload);

  // Everything pending, oldest first; the queue is empty afterwards.
  std::vector<std::string> take_all();

  std::size_t pending() const { return order_.size(); }
  std::size_t pending_bytes() const { return bytes_; }
  std::uint64_t dropped() const { return dropped_; }

 private:
  struct Entry {
    std::string key, payload;
  };
  std::size_t max_keys_;
  std::list<Entry> order_;
  std::unordered_map<std::string, std::list<Entry>::iterator> by_key_;
  std::size_t bytes_ = 0;
  std::uint64_t dropped_ = 0;
};

}  // namespace advee::web
