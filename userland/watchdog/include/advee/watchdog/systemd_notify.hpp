// SPDX-License-Identifier: GPL-2.0
// sd_notify(3) when the supervisor runs as a systemd Type=notify service
// (NOTIFY_SOCKET set): READY=1 once the modules are started, WATCHDOG=1 at
// half the service's WatchdogSec, STATUS= with the module summary. Replaces
// the seed's cron check of the watchdog: systemd restarts a supervisor that
// stops pinging. Without NOTIFY_SOCKET every call does nothing.
#pragma once

#include <chrono>
#include <optional>
#include <string>

namespace advee::watchdog {

class SystemdNotifier {
 public:
  SystemdNotifier();
  bool active() const { return active_; }
  // Half of WATCHDOG_USEC when systemd asked for pings, else nullopt.
  std::optional<std::chrono::microseconds> ping_interval() const { return ping_interval_; }
  void ready(const std::string& status);
  void ping();
  void status(const std::string& status);
  void stopping();

 private:
  bool active_ = false;
  std::optional<std::chrono::microseconds> ping_interval_;
};

}  // namespace advee::watchdog
