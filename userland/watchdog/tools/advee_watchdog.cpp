// SPDX-License-Identifier: GPL-2.0
// advee-watchdog: runs and guards the robot's modules (docs/modules.md).
#include <iostream>

#include "advee/cli.hpp"
#include "advee/module/module.hpp"
#include "advee/watchdog/config.hpp"
#include "advee/watchdog/supervisor.hpp"
#include "advee/watchdog/systemd_notify.hpp"

using namespace advee;

int main(int argc, char** argv) {
  CLI::App app{
      "advee-watchdog: starts the robot modules listed in its configuration, restarts a module\n"
      "whose CM_DATA_STATE announcement is older than dead_after_s (2 s) with exponential\n"
      "back-off, and obeys CM_CMD_STATE for each module (TERMINATE keeps it down, RUN starts it\n"
      "again). Under systemd (Type=notify) it reports READY=1, STATUS= and pings WATCHDOG=1\n"
      "at half of WatchdogSec. The LCM URL comes from the configuration or LCM_DEFAULT_URL.\n"
      "Exit codes: 0 terminated on request, 2 bad command line, 0x41 configuration error (also a\n"
      "module whose program cannot be executed), 0x11 resource error.",
      "advee-watchdog"};
  std::string config_path = "/etc/advee/watchdog.yaml";
  bool check_only = false;
  app.add_option("-c,--config", config_path, "supervisor configuration (YAML)")
      ->capture_default_str();
  app.add_flag("--check", check_only,
               "parse the configuration, check that every module's program can be executed, print "
               "the module list and exit");
  ADVEE_CLI_PARSE(app, argc, argv);

  return module::guarded_main("advee-watchdog", [&] {
    auto cfg = watchdog::load_supervisor_config(config_path);
    watchdog::check_module_programs(cfg);
    if (check_only) {
      for (const auto& m : cfg.modules) {
        std::cout << m.name << " " << m.path;
        for (const auto& a : m.args) std::cout << " " << a;
        std::cout << (m.start ? "" : "  (kept down until RUN)") << "\n";
      }
      return 0;
    }
    cfg.self.extra_signals.push_back(SIGCHLD);
    module::Module self(cfg.self);
    watchdog::SystemdNotifier notifier;
    watchdog::SystemProcesses processes;
    watchdog::Supervisor sup(self, cfg, processes);
    sup.notify_systemd(notifier);
    sup.start();
    return self.run();
  });
}
