// SPDX-License-Identifier: GPL-2.0
// advee-lcmctl: the console end of the module bus.
//   advee-lcmctl echo [--count N] [--timeout S] CHANNEL...   decoded messages, one per line
//   advee-lcmctl state [--manual] TARGET STATE               send CM_CMD_STATE
// The LCM URL is --url or LCM_DEFAULT_URL.
#include <CLI/CLI.hpp>
#include <chrono>
#include <cstdio>
#include <iostream>
#include <lcm/lcm-cpp.hpp>
#include <sstream>
#include <string>
#include <vector>

#include "advee/cli.hpp"
#include "advee/module/state.hpp"
#include "advee/module/time.hpp"
#include "advee/msgs/bus.hpp"
#include "common/cmd_state_t.hpp"
#include "common/data_module_phase_t.hpp"
#include "common/data_state_t.hpp"
#include "common/error_t.hpp"
#include "lowlevel/data_fans_t.hpp"
#include "lowlevel/data_temperature_t.hpp"

using namespace advee;

namespace {

std::string state_name(int v) {
  const auto s = module::state_from_wire(static_cast<std::int8_t>(v));
  return s ? std::string(module::to_string(*s)) : std::to_string(v);
}

template <typename T>
bool decode(const lcm::ReceiveBuffer* rb, T& m) {
  return m.decode(rb->data, 0, static_cast<int>(rb->data_size)) >= 0;
}

// One line per message: "CHANNEL key=value ...". Unknown types: the size.
std::string describe(const lcm::ReceiveBuffer* rb, const std::string& ch) {
  std::ostringstream o;
  o << ch;
  char buf[32];
  if (common::data_state_t m; ch == "CM_DATA_STATE" && decode(rb, m)) {
    o << " module=" << m.module << " state=" << state_name(m.state) << " pid=" << m.pid;
  } else if (common::cmd_state_t c; ch == "CM_CMD_STATE" && decode(rb, c)) {
    o << " module=" << c.module << " target=" << c.target << " state=" << state_name(c.state)
      << " manual=" << int(c.manual);
  } else if (common::error_t e; ch == "CM_DATA_ERROR" && decode(rb, e)) {
    o << " module=" << e.module << " severity=" << int(e.severity) << " type=" << int(e.type)
      << " number=" << e.number << " fatal=" << int(e.fatal) << " text=\"" << e.text << "\"";
  } else if (common::data_module_phase_t p; ch == "CM_DATA_MODULES" && decode(rb, p)) {
    static const char* names[] = {"DOWN", "STARTING", "RUNNING", "TERMINATING", "TERMINATED"};
    o << " module=" << p.module << " target=" << p.target << " phase="
      << (p.phase >= 0 && p.phase <= 4 ? names[p.phase] : "?") << " pid=" << p.pid
      << " restarts=" << p.restarts << " exit=" << p.exit_status << " next_start_ms=" << p.next_start_ms;
  } else if (lowlevel::data_temperature_t t; ch == "LL_DATA_TEMPERATURE" && decode(rb, t)) {
    o << " module=" << t.module;
    for (int i = 0; i < t.count; ++i) {
      std::snprintf(buf, sizeof buf, "%.3f", t.celsius[i]);
      o << " " << t.label[i] << "=" << buf;
    }
  } else if (lowlevel::data_fans_t f; ch == "LL_DATA_FANS" && decode(rb, f)) {
    o << " module=" << f.module;
    for (int i = 0; i < f.count; ++i)
      o << " " << f.label[i] << "=" << f.rpm[i] << " " << f.label[i] << "_fault=" << int(f.fault[i])
        << " " << f.label[i] << "_pwm=" << f.pwm[i];
    o << " fan_fail=" << int(f.fan_fail);
  } else {
    o << " bytes=" << rb->data_size;
  }
  return o.str();
}

struct Echo {
  long count = 0;
  bool reader_gone = false;  // stdout closed (SIGPIPE may be ignored by the caller)
  static void on(const lcm::ReceiveBuffer* rb, const std::string& ch, Echo* self) {
    std::cout << describe(rb, ch) << std::endl;
    self->reader_gone = !std::cout;
    ++self->count;
  }
};

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{"advee-lcmctl: watch and command the Advee modules on LCM", "advee-lcmctl"};
  std::string url;
  app.add_option("--url", url, "LCM URL (default: LCM_DEFAULT_URL, else /etc/advee/lcm.conf, else LCM's default group)");
  app.require_subcommand(1);

  auto* echo = app.add_subcommand("echo", "print decoded messages of the channels, one line each");
  std::vector<std::string> channels;
  long count = 0;
  double timeout_s = 0;
  echo->add_option("--count", count, "exit after this many messages (0: never)");
  echo->add_option("--timeout", timeout_s, "exit after this many seconds (0: never); exit code 1 "
                                           "if --count was not reached");
  echo->add_option("channels", channels, "channel names (regular expressions, LCM syntax)")->required();

  auto* state = app.add_subcommand("state", "send CM_CMD_STATE: ask TARGET to change to STATE");
  std::string target, state_name_arg;
  bool manual = false;
  state->add_option("target", target, "module name, or * for every module")->required();
  state->add_option("state", state_name_arg, "RUN, PAUSE, STOP, TERMINATE, ...")->required();
  state->add_flag("--manual", manual, "an operator's command (needed to enter or leave STOP)");
  ADVEE_CLI_PARSE(app, argc, argv);
  const auto new_state = module::parse_state(state_name_arg);
  if (*state && (!new_state || *new_state == module::State::Unknown))
    return advee::cli::usage_error(app, "no such state " + state_name_arg + " (RUN, PAUSE, STOP, TERMINATE, ...)");

  std::unique_ptr<lcm::LCM> bus;
  try {
    bus = msgs::open_bus(msgs::bus_url(url, "--url"));
  } catch (const msgs::BusUnavailable& e) {
    std::cerr << "advee-lcmctl: " << e.what() << "\n";
    return 1;
  }
  lcm::LCM& lcm = *bus;
  if (*state) {
    const auto s = new_state;
    common::cmd_state_t c;
    c.utime = module::utime_now();
    c.module = "advee-lcmctl";
    c.target = target;
    c.state = static_cast<std::int8_t>(*s);
    c.manual = manual;
    return lcm.publish("CM_CMD_STATE", &c) == 0 ? 0 : 1;
  }
  Echo e;
  // Function-pointer form: see subscription.hpp on the member-function form.
  for (const auto& ch : channels) lcm.subscribeFunction(ch, &Echo::on, &e);
  const auto end = std::chrono::steady_clock::now() +
                   std::chrono::milliseconds(static_cast<long>(timeout_s * 1000));
  while ((count == 0 || e.count < count) && !e.reader_gone) {
    int wait_ms = 1000;
    if (timeout_s > 0) {
      const auto left = std::chrono::duration_cast<std::chrono::milliseconds>(end - std::chrono::steady_clock::now()).count();
      if (left <= 0) break;
      wait_ms = static_cast<int>(std::min<long>(left, 1000));
    }
    if (lcm.handleTimeout(wait_ms) < 0) return 1;
  }
  return count == 0 || e.count >= count ? 0 : 1;
}
