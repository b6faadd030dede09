// SPDX-License-Identifier: GPL-2.0
#include "advee/cli.hpp"

#include <iostream>
#include <string>

namespace advee::cli {

std::string_view version() { return ADVEE_VERSION; }

std::optional<int> parse(CLI::App& app, int argc, const char* const* argv) {
  // An App made without a name takes argv[0]'s at parse time, too late
  // for the version line and for usage_error().
  if (app.get_name().empty() && argc > 0) {
    const std::string_view path = argv[0];
    app.name(std::string(path.substr(path.rfind('/') + 1)));
  }
  if (app.get_option_no_throw("--version") == nullptr)
    app.set_version_flag("--version", app.get_name() + " " + std::string(version()),
                         "print the program's name and version and exit");
  try {
    app.parse(argc, argv);
  } catch (const CLI::Success& e) {  // --help, --help-all, --version
    return app.exit(e) == 0 ? kExitSuccess : kExitFailure;
  } catch (const CLI::ParseError& e) {
    // CLI11 checks required options and subcommands before it complains
    // about arguments it does not know: "--bogus" alone would read "A
    // subcommand is required". The unknown argument is the news.
    const auto unknown = app.remaining(true);
    if (!unknown.empty() && !app.get_allow_extras())
      return usage_error(app, CLI::ExtrasError(unknown).what());
    return usage_error(app, e.what());
  }
  return std::nullopt;
}

int usage_error(const CLI::App& app, std::string_view message) {
  std::cerr << app.get_name() << ": " << message << "\n"
            << "Run with --help for more information.\n";
  return kExitUsage;
}

}  // namespace advee::cli
