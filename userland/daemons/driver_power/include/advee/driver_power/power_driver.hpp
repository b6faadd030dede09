// SPDX-License-Identifier: GPL-2.0
// driver_power (thesis 7.1.2): the BR-PSC1 power controller on the
// full-duplex EIA-422 link. In RUN it reads the output status and currents at
// `rate_hz` and publishes LL_DATA_POWER, and obeys LL_CMD_POWER (switch an
// output with SET_PWR_STATUS; power the computer off or reboot it with the
// configured commands). In every state it forwards the board's PAUSE events
// as LL_EVENT_STOP at once (from the bus's event thread: the stop button
// must not wait for the loop) and publishes LL_DATA_POWER on a POWER event.
#pragma once

#include <atomic>
#include <chrono>
#include <optional>
#include <string>
#include <vector>

#include "advee/module/config.hpp"
#include "advee/module/module.hpp"
#include "advee/module/subscription.hpp"
#include "advee/rs485/devices/psc1.hpp"
#include "advee/rs485_daemon/bus_section.hpp"
#include "advee/rs485_daemon/node_health.hpp"
#include "lowlevel/cmd_power_t.hpp"
#include "lowlevel/data_power_t.hpp"

namespace advee::driver_power {

struct PowerConfig {
  module::ModuleOptions module;
  rs485_daemon::BusSection bus{"power"};  // /dev/rs485/power
  std::uint8_t address = 0x01;
  double rate_hz = 1.0;
  // argv of the commands for LL_CMD_POWER POWEROFF / REBOOT (PATH searched).
  std::vector<std::string> poweroff_command{"systemctl", "poweroff"};
  std::vector<std::string> reboot_command{"systemctl", "reboot"};
};

// Throws module::ConfigError.
PowerConfig parse_power_config(const module::ConfigNode& root);

// Exit details (module::ExitKind::Device + n).
inline constexpr int kExitNoBus = 1;

// Error numbers on CM_DATA_ERROR besides those of rs485_daemon::NodeHealth.
inline constexpr int kErrBadCommand = 10;    // LL_CMD_POWER out of range
inline constexpr int kErrCommandFailed = 11; // poweroff/reboot command failed
inline constexpr int kErrStopEvent = 12;     // PAUSE engaged/released (notice)

// The status bits and currents as LL_DATA_POWER (no battery voltage on the
// PSC1: -1; a channel without sensor or unread currents: -1 A).
lowlevel::data_power_t power_message(std::uint8_t status, const std::optional<rs485::Psc1Currents>& currents,
                                     bool paused);

// Runs argv, waits for it; 0 or a description of the failure.
std::string run_command(const std::vector<std::string>& argv);

class PowerDriver {
 public:
  PowerDriver(module::Module& m, PowerConfig cfg, rs485::Transport& link,
              rs485_daemon::NodeStatusFn node_status = {});
  ~PowerDriver();
  PowerDriver(const PowerDriver&) = delete;
  PowerDriver& operator=(const PowerDriver&) = delete;

  void poll();  // status + currents -> LL_DATA_POWER (in RUN)

 private:
  void on_command(const lowlevel::cmd_power_t& c);
  void publish_status();
  void on_pause_event(const rs485::PauseEvent& e);  // event thread

  module::Module& m_;
  PowerConfig cfg_;
  rs485_daemon::NodeStatusFn node_status_;
  rs485::CallOptions call_;
  rs485::Psc1 psc_;
  rs485_daemon::NodeHealth health_;
  std::optional<std::uint8_t> status_;  // last known output status
  std::optional<rs485::Psc1Currents> currents_;
  std::atomic<bool> paused_{false};
  std::optional<module::Subscription<lowlevel::cmd_power_t>> cmd_sub_;
  rs485::Subscription pause_sub_, power_sub_;  // last: they go first
};

}  // namespace advee::driver_power
