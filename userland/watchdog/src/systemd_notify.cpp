// SPDX-License-Identifier: GPL-2.0
#include "advee/watchdog/systemd_notify.hpp"

#include <systemd/sd-daemon.h>

#include <cstdint>
#include <cstdlib>

namespace advee::watchdog {

SystemdNotifier::SystemdNotifier() {
  const char* sock = std::getenv("NOTIFY_SOCKET");
  active_ = sock && *sock;
  if (!active_) return;
  std::uint64_t usec = 0;
  // > 0 only when WATCHDOG_USEC is set (and WATCHDOG_PID, if set, is ours).
  if (sd_watchdog_enabled(0, &usec) > 0 && usec > 0)
    ping_interval_ = std::chrono::microseconds(usec / 2);
}

void SystemdNotifier::ready(const std::string& status) {
  if (active_) sd_notifyf(0, "READY=1\nSTATUS=%s", status.c_str());
}

void SystemdNotifier::ping() {
  if (active_) sd_notify(0, "WATCHDOG=1");
}

void SystemdNotifier::status(const std::string& status) {
  if (active_) sd_notifyf(0, "STATUS=%s", status.c_str());
}

void SystemdNotifier::stopping() {
  if (active_) sd_notify(0, "STOPPING=1");
}

}  // namespace advee::watchdog
