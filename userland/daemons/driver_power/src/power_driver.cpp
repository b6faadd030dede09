// SPDX-License-Identifier: GPL-2.0
#include "advee/driver_power/power_driver.hpp"

#include <spawn.h>
#include <sys/wait.h>

#include <cerrno>
#include <cmath>
#include <cstring>
#include <lcm/lcm-cpp.hpp>

#include "advee/module/time.hpp"
#include "advee/msgs/channels.hpp"
#include "lowlevel/cmd_power_t.hpp"
#include "lowlevel/data_power_t.hpp"
#include "lowlevel/event_stop_t.hpp"

extern char** environ;

namespace advee::driver_power {

using module::ConfigNode;
using module::ErrorType;
using module::Severity;

PowerConfig parse_power_config(const ConfigNode& root) {
  root.allow_only({"module", "driver_power"});
  PowerConfig c;
  c.module.name = "driver_power";
  if (root.has("module")) module::parse_module_options(root.child("module"), c.module);
  if (!root.has("driver_power")) return c;
  const auto n = root.child("driver_power");
  n.allow_only({"bus", "address", "rate_hz", "poweroff_command", "reboot_command"});
  if (n.has("bus")) c.bus = rs485_daemon::parse_bus_section(n.child("bus"), c.bus.device);
  const auto addr = n.get<unsigned>("address", c.address);
  if (addr > 0xfe) n.fail("address", "node address must be 0x00..0xfe");
  c.address = static_cast<std::uint8_t>(addr);
  c.rate_hz = n.get<double>("rate_hz", c.rate_hz);
  if (!(c.rate_hz >= 0.1 && c.rate_hz <= 50)) n.fail("rate_hz", "must be between 0.1 and 50");
  for (const char* key : {"poweroff_command", "reboot_command"}) {
    if (!n.has(key)) continue;
    if (!n.yaml()[key].IsSequence()) n.fail(key, "expected an argument list such as [systemctl, poweroff]");
    auto argv = n.get<std::vector<std::string>>(key);
    if (argv.empty() || argv[0].empty()) n.fail(key, "needs at least the program");
    (std::string(key) == "reboot_command" ? c.reboot_command : c.poweroff_command) = std::move(argv);
  }
  return c;
}

lowlevel::data_power_t power_message(std::uint8_t status, const std::optional<rs485::Psc1Currents>& currents,
                                     bool paused) {
  lowlevel::data_power_t m{};
  m.battery_v = -1.0f;
  m.num_outputs = static_cast<std::int16_t>(rs485::psc1::kChannels);
  for (std::size_t ch = 0; ch < rs485::psc1::kChannels; ++ch) {
    m.on.push_back((status >> ch) & 1);
    const auto& a = currents ? (*currents)[ch] : std::optional<double>();
    m.current_a.push_back(a ? static_cast<float>(*a) : -1.0f);
  }
  m.paused = paused;
  return m;
}

std::string run_command(const std::vector<std::string>& argv) {
  std::vector<char*> args;
  for (const auto& a : argv) args.push_back(const_cast<char*>(a.c_str()));
  args.push_back(nullptr);
  pid_t pid = 0;
  const int err = ::posix_spawnp(&pid, args[0], nullptr, nullptr, args.data(), environ);
  if (err != 0) return argv[0] + ": " + std::strerror(err);
  int st = 0;
  while (::waitpid(pid, &st, 0) < 0) {
    if (errno != EINTR) return argv[0] + ": waitpid: " + std::strerror(errno);
  }
  if (WIFEXITED(st) && WEXITSTATUS(st) == 0) return {};
  return argv[0] + (WIFEXITED(st) ? " exited with " + std::to_string(WEXITSTATUS(st))
                                  : " killed by signal " + std::to_string(WTERMSIG(st)));
}

PowerDriver::PowerDriver(module::Module& m, PowerConfig cfg, rs485::Transport& link,
                         rs485_daemon::NodeStatusFn node_status)
    : m_(m),
      cfg_(std::move(cfg)),
      node_status_(std::move(node_status)),
      call_(cfg_.bus.config.timeout, cfg_.bus.config.retries),
      psc_(link, cfg_.address),
      health_(m.errors(), "psc1", cfg_.address) {
  cmd_sub_.emplace(m_.lcm(), std::string(msgs::kCmdPower.name),
                   [this](const lowlevel::cmd_power_t& c) { on_command(c); });
  pause_sub_ = psc_.on_pause([this](const rs485::PauseEvent& e) { on_pause_event(e); });
  power_sub_ = psc_.on_power([this](const rs485::PowerEvent& e) {
    m_.post([this, e] {
      status_ = e.status;
      publish_status();
    });
  });
  m_.every(std::chrono::nanoseconds(static_cast<std::int64_t>(1e9 / cfg_.rate_hz)), [this] { poll(); });
}

PowerDriver::~PowerDriver() {
  pause_sub_.reset();
  power_sub_.reset();
  cmd_sub_.reset();
}

void PowerDriver::on_pause_event(const rs485::PauseEvent& e) {
  lowlevel::event_stop_t s{};
  s.utime = module::utime_now();
  s.module = m_.name();
  s.stop = e.engaged;
  s.source = lowlevel::event_stop_t::SOURCE_PSC1;
  paused_ = e.engaged;
  m_.lcm().publish(std::string(msgs::kEventStop.name), &s);  // LCM publishing is thread-safe
  m_.errors().report(Severity::Notice, ErrorType::Device, kErrStopEvent,
                     std::string("PAUSE ") + (e.engaged ? "engaged" : "released") + " (sources 0x" +
                         [&] {
                           char b[4];
                           std::snprintf(b, sizeof b, "%02x", e.sources);
                           return std::string(b);
                         }() + ")");
  m_.post([this] {
    if (status_) publish_status();
  });
}

void PowerDriver::publish_status() {
  if (!status_) return;
  auto msg = power_message(*status_, currents_, paused_);
  msg.utime = module::utime_now();
  msg.module = m_.name();
  m_.lcm().publish(std::string(msgs::kDataPower.name), &msg);
}

void PowerDriver::poll() {
  if (!health_.may_poll(node_status_)) return;
  auto st = psc_.power_status(call_);
  health_.record("GET_PWR_STATUS", st ? std::error_code() : st.error(), node_status_);
  if (!st) return;
  status_ = *st;
  auto cur = psc_.currents(call_);
  health_.record("GET_CURRENTS", cur ? std::error_code() : cur.error(), node_status_);
  if (cur)
    currents_ = *cur;
  else
    currents_.reset();
  publish_status();
}

void PowerDriver::on_command(const lowlevel::cmd_power_t& cmd) {
  const auto* c = &cmd;
  if (m_.state() != module::State::Run) {
    m_.errors().report(Severity::Warning, ErrorType::Unknown, kErrBadCommand,
                       "LL_CMD_POWER from " + c->module + " ignored: module is in " +
                           std::string(module::to_string(m_.state())));
    return;
  }
  switch (c->action) {
    case lowlevel::cmd_power_t::ACTION_SET_OUTPUT: {
      if (c->output < 0 || c->output >= static_cast<int>(rs485::psc1::kChannels)) {
        m_.errors().report(Severity::Warning, ErrorType::Unknown, kErrBadCommand,
                           "LL_CMD_POWER from " + c->module + ": output " + std::to_string(c->output) +
                               " out of 0..7");
        return;
      }
      const auto bit = static_cast<std::uint8_t>(1u << c->output);
      auto st = psc_.set_power_status(bit, c->on ? bit : 0, call_);
      health_.record("SET_PWR_STATUS", st ? std::error_code() : st.error(), node_status_);
      if (!st) return;
      status_ = *st;
      m_.errors().report(Severity::Notice, ErrorType::Unknown, 0,
                         "output " + std::to_string(c->output) + (c->on ? " on" : " off") + " for " + c->module);
      publish_status();
      return;
    }
    case lowlevel::cmd_power_t::ACTION_POWEROFF:
    case lowlevel::cmd_power_t::ACTION_REBOOT: {
      const bool off = c->action == lowlevel::cmd_power_t::ACTION_POWEROFF;
      const auto& argv = off ? cfg_.poweroff_command : cfg_.reboot_command;
      m_.errors().report(Severity::Notice, ErrorType::Unknown, 0,
                         std::string(off ? "power-off" : "reboot") + " requested by " + c->module + ": " + argv[0]);
      if (auto why = run_command(argv); !why.empty())
        m_.errors().report(Severity::Error, ErrorType::Resource, kErrCommandFailed,
                           std::string(off ? "power-off" : "reboot") + " command failed: " + why);
      return;
    }
    default:
      m_.errors().report(Severity::Warning, ErrorType::Unknown, kErrBadCommand,
                         "LL_CMD_POWER from " + c->module + ": unknown action " + std::to_string(c->action));
  }
}

}  // namespace advee::driver_power
