// SPDX-License-Identifier: GPL-2.0
// The per-run log directory (thesis 3.2): <root>/YYYY_MM_DD_HH_MM_SS/, one per
// start of the system. The supervisor creates it and hands it to the modules
// it starts in ADVEE_LOG_DIR, so one run's logs stay together; a module
// started by hand creates its own.
#pragma once

#include <chrono>
#include <filesystem>

namespace advee::module {

inline constexpr const char* kLogDirEnv = "ADVEE_LOG_DIR";

// Creates root (and parents) and a new run directory named after `when` (local
// time); a suffix _2, _3, ... keeps two runs in the same second apart.
// Throws std::filesystem::filesystem_error.
std::filesystem::path create_run_log_dir(const std::filesystem::path& root,
                                         std::chrono::system_clock::time_point when =
                                             std::chrono::system_clock::now());

}  // namespace advee::module
