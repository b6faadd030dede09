// SPDX-License-Identifier: GPL-2.0
// For callbacks that an object hands to something that outlives it (SDO
// completions queued in the master's SdoClient): wrap() them with the
// object's Lifetime. Once the Lifetime is gone (with its owner) or renew()ed
// (the owner starts over), the wrapped callbacks do nothing when called.
#pragma once

#include <memory>
#include <utility>

namespace advee::canopen {

class Lifetime {
 public:
  Lifetime() = default;
  Lifetime(const Lifetime&) = delete;
  Lifetime& operator=(const Lifetime&) = delete;

  template <typename F>
  auto wrap(F f) const {
    return [alive = std::weak_ptr<const char>(token_), f = std::move(f)](auto&&... args) mutable {
      if (!alive.expired()) f(std::forward<decltype(args)>(args)...);
    };
  }
  // Callbacks wrapped so far do nothing from now on.
  void renew() { token_ = std::make_shared<const char>(0); }

 private:
  std::shared_ptr<const char> token_ = std::make_shared<const char>(0);
};

}  // namespace advee::canopen
