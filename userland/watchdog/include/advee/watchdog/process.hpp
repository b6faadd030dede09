// SPDX-License-Identifier: GPL-2.0
// Starting and signalling a supervised process. Each module runs in its own
// process group, so signals reach whatever it started too.
#pragma once

#include <sys/types.h>

#include <map>
#include <string>

#include "advee/watchdog/config.hpp"

namespace advee::watchdog {

// fork + execve of spec.path with spec.args and the supervisor's environment
// plus spec.env plus extra_env. The child gets an empty signal mask and no
// inherited descriptors above stderr. Throws std::system_error when fork
// fails; an exec failure shows as exit code 127 of the child.
pid_t spawn_module(const ModuleSpec& spec, const std::map<std::string, std::string>& extra_env);

// Signal the process group of pid (falls back to pid alone).
void signal_group(pid_t pid, int signo);

}  // namespace advee::watchdog
