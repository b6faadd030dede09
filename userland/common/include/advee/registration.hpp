// SPDX-License-Identifier: GPL-2.0
// An RAII registration (a subscription, a listener, a polled service):
// destroying or reset()ting it runs its cancel function, once. Move-only.
// Whoever hands one out makes the cancel function safe to run after the
// registry itself is gone (e.g. through a weak_ptr), so the two may die in
// any order.
#pragma once

#include <functional>
#include <utility>

namespace advee {

class Registration {
 public:
  Registration() = default;
  explicit Registration(std::function<void()> cancel) : cancel_(std::move(cancel)) {}
  ~Registration() { reset(); }
  Registration(Registration&& o) noexcept : cancel_(std::exchange(o.cancel_, {})) {}
  Registration& operator=(Registration&& o) noexcept {
    if (this != &o) {
      reset();
      cancel_ = std::exchange(o.cancel_, {});
    }
    return *this;
  }
  Registration(const Registration&) = delete;
  Registration& operator=(const Registration&) = delete;

  void reset() {
    if (auto c = std::exchange(cancel_, {})) c();
  }
  explicit operator bool() const { return static_cast<bool>(cancel_); }

 private:
  std::function<void()> cancel_;
};

}  // namespace advee
