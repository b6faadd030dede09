// SPDX-License-Identifier: GPL-2.0
// advee-diagnostic-center: the console diagnostic centre of the Advee low level
// (thesis 3.7). Interactive ncurses views, or --text: a plain-text summary
// every --period for --for seconds. docs/diagnostic-center.md.
#include <poll.h>
#include <signal.h>
#include <unistd.h>

#include <CLI/CLI.hpp>
#include <chrono>
#include <cmath>
#include <csignal>
#include <cstdio>
#include <cstdlib>
#include <iostream>
#include <lcm/lcm-cpp.hpp>
#include <string>

#include "advee/cli.hpp"
#include "advee/diagcenter/commands.hpp"
#include "advee/diagcenter/controller.hpp"
#include "advee/diagcenter/duration.hpp"
#include "advee/diagcenter/model.hpp"
#include "advee/diagcenter/text_summary.hpp"
#include "advee/msgs/bus.hpp"
#include "tui.hpp"

using namespace advee::diagcenter;

namespace {

// The program's name (messages, --help, --version) follows the installed
// names (docs/command-line.md "Names"); on LCM it stays the thesis's module
// name: commands carry it as their sender, and the other tools know it.
constexpr const char* kName = "advee-diagnostic-center";
constexpr const char* kLcmName = "diagnostic_center";

double mono_now() {
  return std::chrono::duration<double>(std::chrono::steady_clock::now().time_since_epoch()).count();
}

volatile std::sig_atomic_t g_quit_signal = 0;
void on_quit_signal(int sig) { g_quit_signal = sig; }

// SIGINT/SIGTERM/SIGHUP end the interactive loop (the terminal is restored
// and a manual drive stopped) instead of killing the process. Installed
// before initscr(), so ncurses keeps them; no SA_RESTART, so poll() wakes.
void install_quit_handlers() {
  struct sigaction sa {};
  sa.sa_handler = on_quit_signal;
  sigemptyset(&sa.sa_mask);
  for (int s : {SIGINT, SIGTERM, SIGHUP}) sigaction(s, &sa, nullptr);
}

// Handle every LCM message that is waiting, without blocking.
bool drain(lcm::LCM& lcm) {
  for (;;) {
    const int n = lcm.handleTimeout(0);
    if (n < 0) return false;
    if (n == 0) return true;
  }
}

enum class Wait { Ok, LcmFailed, TerminalGone };

// Wait up to timeout_s for LCM or stdin and handle the LCM messages.
Wait wait_input(lcm::LCM& lcm, bool with_stdin, double timeout_s) {
  pollfd fds[2] = {{lcm.getFileno(), POLLIN, 0}, {STDIN_FILENO, POLLIN, 0}};
  const int ms = std::max(0, static_cast<int>(std::ceil(timeout_s * 1000)));
  const int r = ::poll(fds, with_stdin ? 2 : 1, ms);
  if (r > 0 && (fds[0].revents & POLLIN) && !drain(lcm)) return Wait::LcmFailed;
  // A hung-up terminal without SIGHUP would wake poll() at once forever.
  if (r > 0 && with_stdin && (fds[1].revents & (POLLHUP | POLLERR | POLLNVAL))) return Wait::TerminalGone;
  return Wait::Ok;  // timeout, messages, a key, or EINTR (a signal)
}

int run_text(lcm::LCM& lcm, Model& model, double duration_s, double period_s, const std::string& url) {
  const double start = mono_now();
  const double end = start + duration_s;
  double next = start + period_s;
  for (;;) {
    const double now = mono_now();
    if (now >= next - 1e-6) {
      std::cout << text_summary(model, now, now - start) << std::endl;  // a block per period, flushed
      next += period_s;
      if (next > end + 1e-6) break;
    }
    if (wait_input(lcm, false, std::min(next, end) - mono_now()) != Wait::Ok) {
      std::cerr << kName << ": LCM failed while receiving\n";
      return 1;
    }
  }
  if (model.messages() == 0) {
    std::cerr << kName << ": no LCM message arrived in " << duration_s << " s on " << url
              << "; are the modules running, and does the host have a multicast route "
                 "(ip route add 224.0.0.0/4 dev lo)?\n";
    return advee::cli::kExitFailure;
  }
  return 0;
}

int run_tui(lcm::LCM& lcm, Model& model, const DriveLimits& limits, const std::string& url) {
  if (!isatty(STDIN_FILENO) || !isatty(STDOUT_FILENO)) {
    std::cerr << kName << ": the interactive view needs a terminal; use --text --for DURATION\n";
    return advee::cli::kExitUsage;
  }
  LcmCommandSink sink(lcm, kLcmName);
  Controller ctl(model, sink, limits);
  install_quit_handlers();
  tui::Screen screen;
  constexpr double kRedrawS = 0.2;  // data changes at 4 Hz; keys redraw at once
  double next_draw = 0;
  while (!ctl.quit() && !g_quit_signal) {
    const double now = mono_now();
    bool dirty = false;
    for (Key k = screen.read_key(); k.kind != Key::None; k = screen.read_key())
      dirty |= ctl.on_key(k, mono_now());
    ctl.tick(mono_now());
    if (dirty || now >= next_draw) {
      tui::draw(model, ctl, mono_now(), url.c_str());
      next_draw = mono_now() + kRedrawS;
    }
    if (ctl.quit()) break;
    // Wake for the next 10 Hz motion command, the next redraw, a key or LCM.
    const double wake = std::min(next_draw, mono_now() + Controller::kMotionRepeatS / 2);
    const Wait w = wait_input(lcm, true, wake - mono_now());
    if (w == Wait::TerminalGone) break;
    if (w == Wait::LcmFailed) {
      ctl.shutdown();
      return 1;
    }
  }
  ctl.shutdown();  // a signal in the middle of a manual drive stops the robot
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{
      "advee-diagnostic-center: the console diagnostic centre of the Advee robot's low level.\n"
      "Shows every LCM channel of the modules (states and restarts, errors, odometry position\n"
      "estimate, motion command and drives, ranges around the robot, beacons, temperatures,\n"
      "fans, power outputs, PAUSE) and sends operator commands: module states, power outputs,\n"
      "manual driving with the arrow keys, steering homing.",
      kName};
  std::string url;
  bool text = false;
  std::string for_text, period_text = "1s";
  DriveLimits limits;
  double steer_step_deg = limits.steering_step_rad * 180 / M_PI;
  app.add_option("--lcm", url, "LCM URL (default: LCM_DEFAULT_URL, else /etc/advee/lcm.conf, else LCM's default group)");
  app.add_flag("--text", text, "no terminal UI: print a plain-text summary every --period to stdout");
  app.add_option("--for", for_text, "with --text: run for DURATION (30s, 500ms, 2m; a bare number is seconds) and exit");
  app.add_option("--period", period_text, "with --text: time between two summaries (default 1s)");
  app.add_option("--speed-step", limits.speed_step_mps, "manual driving: m/s per up/down key (default 0.1)")
      ->check(CLI::Range(0.01, 1.0));
  app.add_option("--max-speed", limits.max_speed_mps, "manual driving: speed limit, m/s (default 1.0)")
      ->check(CLI::Range(0.01, 3.0));
  app.add_option("--steer-step", steer_step_deg, "manual driving: degrees per left/right key (default 5)")
      ->check(CLI::Range(0.5, 30.0));
  app.footer(
      "VIEWS AND KEYS (interactive)\n"
      "  1 or F1  summary: module states, odometry position, motion command and drives, ranges\n"
      "           around the robot, PAUSE, temperatures, fans, power outputs, beacons, last error.\n"
      "           Arrow keys drive: up/down change the speed, left/right the steering, in steps;\n"
      "           the first arrow key switches manual driving on, which repeats LL_CMD_MOTION at\n"
      "           10 Hz (driver_canbus quick-stops after 1 s without one); m switches it off\n"
      "           (after one zero command); h sends LL_CMD_HOMING (steering); o resets the\n"
      "           odometry position to 0, 0.\n"
      "  2 or F2  errors (CM_DATA_ERROR), newest at the bottom: up/down scroll, c clears.\n"
      "  3 or F3  modules: state, pid, age of the last announcement, the supervisor's phase,\n"
      "           restarts and exit status. up/down select; r RUN, p PAUSE, s STOP,\n"
      "           t t (twice within 3 s) TERMINATE send CM_CMD_STATE (manual) to the selected\n"
      "           module; the supervisor keeps a terminated module down until RUN.\n"
      "  4 or F4  power outputs (LL_CMD_POWER): up/down select, enter toggles, n on, f off.\n"
      "  space    stop in every view: speed and steering 0 at once.\n"
      "  q        quit (a manual drive is stopped first; so are SIGINT and SIGTERM).\n"
      "  Data older than three periods of its channel is dimmed and marked (Ns old).\n\n"
      "TEXT MODE\n"
      "  advee-diagnostic-center --text --for 30s [--period 1s] prints one block per period:\n"
      "  lines 'summary', 'pose_odo', 'pose_true', 'odo', 'motion', 'drives', 'modules',\n"
      "  'module_pids', 'module_restarts', 'module_phases', 'module_ages', 'srf', 'ir',\n"
      "  'beacons', 'temps', 'fans', 'power', 'stop', 'errors', each 'topic key=value ...';\n"
      "  'none' when nothing arrived; age=SECONDS and stale=1 (docs/diagnostic-center.md).\n\n"
      "EXIT STATUS\n"
      "  0   quit, or --text ran for its duration and received messages\n"
      "  1   LCM failed, or --text: no LCM message arrived at all during the duration\n"
      "  2   bad command line, or the interactive view without a terminal\n");
  ADVEE_CLI_PARSE(app, argc, argv);
  limits.steering_step_rad = steer_step_deg * M_PI / 180;
  const auto period = parse_duration(period_text);
  if (!period || *period < 0.05)
    return advee::cli::usage_error(app, "--period " + period_text + ": a duration of at least 50ms, e.g. 1s");
  std::optional<double> duration;
  if (!for_text.empty()) {
    duration = parse_duration(for_text);
    if (!duration || *duration <= 0)
      return advee::cli::usage_error(app, "--for " + for_text + ": a duration such as 30s, 500ms, 2m");
  }
  if (text && !duration) return advee::cli::usage_error(app, "--text needs --for DURATION");
  if (!text && duration) return advee::cli::usage_error(app, "--for is for --text");

  const auto bus_url = advee::msgs::bus_url(url);
  std::unique_ptr<lcm::LCM> bus;
  try {
    bus = advee::msgs::open_bus(bus_url);
  } catch (const advee::msgs::BusUnavailable& e) {
    std::cerr << kName << ": " << e.what() << "\n";
    return 1;
  }
  lcm::LCM& lcm = *bus;
  url = bus_url.url;  // the URL in effect, for the display
  Model model;
  model.subscribe(lcm, mono_now);
  if (text) return run_text(lcm, model, *duration, *period, url);
  return run_tui(lcm, model, limits, url);
}
