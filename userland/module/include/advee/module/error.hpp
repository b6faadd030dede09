// SPDX-License-Identifier: GPL-2.0
// Error reporting of the modules (the thesis's liberror, 3.3.1): an error has a
// number, a text, a fatality flag, a type, a severity and the source location.
// A report is printed to stderr from `print_severity` up, published as
// common.error_t from `send_severity` up, and every report goes to the
// module's log file when it has one.
#pragma once

#include <cstdint>
#include <fstream>
#include <mutex>
#include <optional>
#include <source_location>
#include <string>
#include <string_view>

namespace lcm {
class LCM;
}

namespace advee::module {

enum class Severity : std::int8_t { Notice = 0, Warning = 1, Error = 2 };
enum class ErrorType : std::int8_t { Unknown = 0, Timeout = 1, Resource = 2, Device = 3 };

std::string_view to_string(Severity s);
std::string_view to_string(ErrorType t);
std::optional<Severity> parse_severity(std::string_view s);  // "notice", "warning", "error", "none"

// "none" as a threshold: nothing passes.
inline constexpr std::int8_t kSeverityNone = 3;

struct Error {
  int number = 0;
  std::string text;
  bool fatal = false;
  ErrorType type = ErrorType::Unknown;
  Severity severity = Severity::Error;
  std::string file;
  unsigned line = 0;
};

std::string format_error(std::string_view module, const Error& e);  // one line

class ErrorReporter {
 public:
  struct Config {
    std::int8_t print_severity = static_cast<std::int8_t>(Severity::Warning);
    std::int8_t send_severity = static_cast<std::int8_t>(Severity::Warning);
    std::string channel = "CM_DATA_ERROR";
  };

  // lcm may be null: nothing is published.
  ErrorReporter(std::string module, Config cfg, lcm::LCM* lcm);

  void set_log_file(const std::string& path);  // appends; throws std::system_error
  // Thread-safe.
  void report(const Error& e);
  void report(Severity sev, ErrorType type, int number, std::string text, bool fatal = false,
              std::source_location loc = std::source_location::current());

  // What the thresholds let through (for tests and for callers that build
  // expensive texts).
  bool prints(Severity s) const { return static_cast<std::int8_t>(s) >= cfg_.print_severity; }
  bool sends(Severity s) const { return static_cast<std::int8_t>(s) >= cfg_.send_severity; }
  const std::string& module() const { return module_; }

 private:
  std::string module_;
  Config cfg_;
  lcm::LCM* lcm_;
  std::mutex mutex_;
  std::ofstream log_;
};

}  // namespace advee::module
