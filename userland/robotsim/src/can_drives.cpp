// SPDX-License-Identifier: GPL-2.0
#include "advee/robotsim/can_drives.hpp"

#include <stdexcept>

namespace advee::robotsim {

CanDrives::CanDrives(const std::string& ifname, const DriveUnits& units) {
  port_ = std::make_unique<canopen::CanPort>(loop_, canopen::CanSocket::open(ifname), [this](const canopen::CanFrame& f) {
    const std::lock_guard lock(mutex_);
    drives_->handle(f);
  });
  drives_ = std::make_unique<DrivePair>(units, port_->sender(), canopen::system_monotonic_clock());
  loop_.add_timer_source(
      [this] {
        const std::lock_guard lock(mutex_);
        return drives_->deadline();
      },
      [this] {
        const std::lock_guard lock(mutex_);
        drives_->poll();
      });
  // The boot-up frames go out from the loop thread, the only one that sends.
  loop_.post([this] {
    const std::lock_guard lock(mutex_);
    drives_->power_on();
  });
  thread_ = std::thread([this] {
    try {
      loop_.run();
    } catch (...) {
      const std::lock_guard lock(mutex_);
      failure_ = std::current_exception();
    }
  });
}

CanDrives::~CanDrives() {
  loop_.stop();
  if (thread_.joinable()) thread_.join();
}

void CanDrives::check_thread() const {
  if (!failure_) return;
  try {
    std::rethrow_exception(failure_);
  } catch (const std::exception& e) {
    throw std::runtime_error(std::string("simulated drives stopped: ") + e.what());
  }
}

DriveCommand CanDrives::command(double) {
  const std::lock_guard lock(mutex_);
  check_thread();
  const DriveMotion m = drives_->motion();
  return {m.speed_mps, m.steering_rad};
}

DriveStatus CanDrives::status() {
  const std::lock_guard lock(mutex_);
  return {drives_->epos().state(), drives_->icla().state(), drives_->epos().velocity(), drives_->icla().position()};
}

void CanDrives::inject_fault(std::uint8_t node, std::uint16_t code) {
  // inject_fault sends an EMCY: that must happen on the loop thread.
  loop_.post([this, node, code] {
    const std::lock_guard lock(mutex_);
    (node == drives_->units().steering_node ? drives_->icla() : drives_->epos()).inject_fault(code);
  });
}

bool CanDrives::toggle_heartbeat_silence() {
  const std::lock_guard lock(mutex_);
  const bool silent = !drives_->epos().faults().heartbeat_silent;
  drives_->epos().faults().heartbeat_silent = silent;
  drives_->icla().faults().heartbeat_silent = silent;
  return silent;
}

}  // namespace advee::robotsim
