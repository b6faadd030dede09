// SPDX-License-Identifier: GPL-2.0
// The supervisor's configuration file (YAML): its own module: section, the
// supervision timings and the modules to run (thesis 3.6 modules.txt).
#pragma once

#include <map>
#include <string>
#include <vector>

#include "advee/module/config.hpp"
#include "advee/watchdog/backoff.hpp"

namespace advee::watchdog {

struct ModuleSpec {
  std::string name;                        // the name it announces on CM_DATA_STATE
  std::string path;                        // executable; relative to the config file's directory
  std::vector<std::string> args;           // argv[1..]
  std::map<std::string, std::string> env;  // added to the supervisor's environment
  bool start = true;                       // false: kept down until CM_CMD_STATE RUN
};

struct SupervisorConfig {
  module::ModuleOptions self;  // name defaults to "watchdog"
  Millis dead_after{2000};     // announcement older than this: dead (thesis: 2 s)
  Millis check_period{200};    // how often the list is checked (thesis: 200 ms)
  Millis term_grace{2000};     // SIGTERM -> SIGKILL
  Millis startup_grace{5000};  // from start to the first announcement
  BackoffConfig backoff;
  std::vector<ModuleSpec> modules;
};

// Throws module::ConfigError naming the file, line and key.
SupervisorConfig parse_supervisor_config(const module::ConfigNode& root);
SupervisorConfig load_supervisor_config(const std::string& path);

// Throws module::ConfigError naming every module whose program cannot be
// executed (missing, not a regular file, not executable): started, it would
// exit 127 at every restart.
void check_module_programs(const SupervisorConfig& config);

}  // namespace advee::watchdog
