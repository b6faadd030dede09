// SPDX-License-Identifier: GPL-2.0
// Thesis 6.5: when no motion command arrives for a while (1 s on the robot),
// the motion layer stops the propulsion with quick stop. The watchdog fires
// once per silence; the next command re-arms it.
#pragma once

#include <functional>
#include <optional>

#include "advee/canopen/master.hpp"

namespace advee::canopen {

class MotionWatchdog final : public TimedService {
 public:
  MotionWatchdog(Master& master, Duration timeout, std::function<void()> on_expire);
  MotionWatchdog(const MotionWatchdog&) = delete;
  MotionWatchdog& operator=(const MotionWatchdog&) = delete;

  void feed();  // a motion command arrived
  bool expired() const { return expired_; }

  void poll() override;
  std::optional<TimePoint> deadline() const override;

 private:
  Master& master_;
  Duration timeout_;
  std::function<void()> on_expire_;
  std::optional<TimePoint> last_;
  bool expired_ = false;
  Registration service_;  // last: polled only while everything above exists
};

}  // namespace advee::canopen
