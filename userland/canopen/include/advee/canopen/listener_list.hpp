// SPDX-License-Identifier: GPL-2.0
// Callbacks keyed by a registration id. call() runs every callback that is
// still registered when its turn comes, so a callback may remove itself or
// any other one (and destroy that one's owner) while the list is called.
#pragma once

#include <cstdint>
#include <functional>
#include <map>
#include <memory>
#include <utility>
#include <vector>

namespace advee::canopen {

template <typename... Args>
class ListenerList {
 public:
  using Fn = std::function<void(Args...)>;
  using Id = std::uint64_t;

  Id add(Fn fn) {
    list_.emplace(next_, std::make_shared<Fn>(std::move(fn)));
    return next_++;
  }
  void remove(Id id) { list_.erase(id); }
  bool empty() const { return list_.empty(); }

  void call(Args... args) {
    // A snapshot, and each callback kept alive by its own reference while it
    // runs (it may remove itself).
    const std::vector<std::pair<Id, std::shared_ptr<Fn>>> snapshot(list_.begin(), list_.end());
    for (const auto& [id, fn] : snapshot)
      if (list_.count(id) != 0) (*fn)(args...);
  }

 private:
  std::map<Id, std::shared_ptr<Fn>> list_;
  Id next_ = 1;
};

}  // namespace advee::canopen
