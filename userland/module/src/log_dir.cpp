// SPDX-License-Identifier: GPL-2.0
#include "advee/module/log_dir.hpp"

#include <ctime>
#include <string>

namespace advee::module {

std::filesystem::path create_run_log_dir(const std::filesystem::path& root,
                                         std::chrono::system_clock::time_point when) {
  std::filesystem::create_directories(root);
  const std::time_t t = std::chrono::system_clock::to_time_t(when);
  std::tm tm{};
  localtime_r(&t, &tm);
  char name[32];
  std::strftime(name, sizeof name, "%Y_%m_%d_%H_%M_%S", &tm);
  for (int n = 1;; ++n) {
    auto dir = root / (n == 1 ? std::string(name) : std::string(name) + "_" + std::to_string(n));
    // create_directory is false when it exists: another run of the same second.
    if (std::filesystem::create_directory(dir)) return dir;
  }
}

}  // namespace advee::module
