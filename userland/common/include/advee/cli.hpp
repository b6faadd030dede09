// SPDX-License-Identifier: GPL-2.0
// The command-line conventions of every Advee program, in one place
// (docs/command-line.md):
//   exit status 0 success (also after --help and --version),
//               1 runtime failure (a device, the network, a file),
//               2 usage error: a bad option or argument, found before any I/O;
//   the robot modules (advee/module/exit_code.hpp) report runtime failures
//   with the thesis's codes instead of 1: 0x10+N resource, 0x20+N device,
//   0x40+N other;
//   --version prints "PROGRAM VERSION", the version of the build
//   (debian/changelog, read by userland/CMakeLists.txt).
#pragma once

#include <CLI/CLI.hpp>
#include <optional>
#include <string_view>

namespace advee::cli {

inline constexpr int kExitSuccess = 0;
inline constexpr int kExitFailure = 1;
inline constexpr int kExitUsage = 2;

// The version of this build, e.g. "0.1.0".
std::string_view version();

// Adds --version to app and parses the command line. nullopt: carry on;
// otherwise the status main returns: 0 after --help or --version (printed
// on stdout), kExitUsage after a parse error (CLI11's message, which names
// the option, and a pointer to --help on stderr).
std::optional<int> parse(CLI::App& app, int argc, const char* const* argv);

// A usage error found after parsing (a value CLI11 cannot check): prints
// "PROGRAM: MESSAGE" and the --help hint on stderr; returns kExitUsage.
int usage_error(const CLI::App& app, std::string_view message);

}  // namespace advee::cli

// In main: ADVEE_CLI_PARSE(app, argc, argv); in place of CLI11_PARSE.
#define ADVEE_CLI_PARSE(app, argc, argv)                                   \
  do {                                                                     \
    if (const auto advee_cli_status_ = ::advee::cli::parse(app, argc, argv)) \
      return *advee_cli_status_;                                           \
  } while (0)
