// SPDX-License-Identifier: GPL-2.0
// A typed LCM subscription to a std::function, unsubscribed on destruction.
// It goes through LCM's function-pointer interface with itself as context:
// LCM's pointer-to-member-function interface trips GCC's UBSan
// ("member access within misaligned address 0x000000000001" inside
// lcm-cpp-impl.hpp) and takes no lambdas.
#pragma once

#include <functional>
#include <lcm/lcm-cpp.hpp>
#include <string>

namespace advee::module {

template <typename Msg>
class Subscription {
 public:
  Subscription(lcm::LCM& lcm, const std::string& channel, std::function<void(const Msg&)> fn)
      : lcm_(lcm), fn_(std::move(fn)) {
    sub_ = lcm_.subscribeFunction(channel, &Subscription::dispatch, this);
  }
  ~Subscription() {
    if (sub_) lcm_.unsubscribe(sub_);
  }
  Subscription(const Subscription&) = delete;
  Subscription& operator=(const Subscription&) = delete;

 private:
  static void dispatch(const lcm::ReceiveBuffer*, const std::string&, const Msg* m,
                       Subscription* self) {
    self->fn_(*m);
  }
  lcm::LCM& lcm_;
  std::function<void(const Msg&)> fn_;
  lcm::Subscription* sub_ = nullptr;
};

}  // namespace advee::module
