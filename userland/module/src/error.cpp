// SPDX-License-Identifier: GPL-2.0
#include "advee/module/error.hpp"

#include <unistd.h>

#include <cctype>
#include <filesystem>
#include <iostream>
#include <lcm/lcm-cpp.hpp>
#include <system_error>

#include "advee/module/time.hpp"
#include "common/error_t.hpp"

namespace advee::module {

std::string_view to_string(Severity s) {
  switch (s) {
    case Severity::Notice: return "notice";
    case Severity::Warning: return "warning";
    case Severity::Error: return "error";
  }
  return "?";
}

std::string_view to_string(ErrorType t) {
  switch (t) {
    case ErrorType::Unknown: return "unknown";
    case ErrorType::Timeout: return "timeout";
    case ErrorType::Resource: return "resource";
    case ErrorType::Device: return "device";
  }
  return "?";
}

std::optional<Severity> parse_severity(std::string_view s) {
  std::string low;
  for (char c : s) low += static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  for (Severity v : {Severity::Notice, Severity::Warning, Severity::Error})
    if (to_string(v) == low) return v;
  return std::nullopt;
}

std::string format_error(std::string_view module, const Error& e) {
  std::string s(module);
  s += ": ";
  s += to_string(e.severity);
  if (e.fatal) s += " (fatal)";
  s += ": ";
  s += e.text;
  // Type and number only when they say something; the location always.
  std::string tail;
  if (e.type != ErrorType::Unknown || e.number != 0)
    tail = std::string(to_string(e.type)) + " " + std::to_string(e.number);
  if (!e.file.empty())
    tail += (tail.empty() ? "" : ", ") + std::filesystem::path(e.file).filename().string() + ":" +
            std::to_string(e.line);
  if (!tail.empty()) s += " [" + tail + "]";
  return s;
}

ErrorReporter::ErrorReporter(std::string module, Config cfg, lcm::LCM* lcm)
    : module_(std::move(module)), cfg_(std::move(cfg)), lcm_(lcm) {}

void ErrorReporter::set_log_file(const std::string& path) {
  std::lock_guard lock(mutex_);
  log_.open(path, std::ios::app);
  if (!log_) throw std::system_error(errno, std::generic_category(), "cannot open " + path);
}

void ErrorReporter::report(const Error& e) {
  const std::string line = format_error(module_, e);
  std::lock_guard lock(mutex_);
  if (prints(e.severity)) std::cerr << line << std::endl;
  if (log_.is_open()) log_ << utime_now() << " " << line << std::endl;
  if (lcm_ && sends(e.severity)) {
    common::error_t m;
    m.utime = utime_now();
    m.module = module_;
    m.number = e.number;
    m.text = e.text;
    m.fatal = e.fatal;
    m.type = static_cast<std::int8_t>(e.type);
    m.severity = static_cast<std::int8_t>(e.severity);
    m.file = e.file;
    m.line = static_cast<std::int32_t>(e.line);
    lcm_->publish(cfg_.channel, &m);
  }
}

void ErrorReporter::report(Severity sev, ErrorType type, int number, std::string text, bool fatal,
                           std::source_location loc) {
  report(Error{number, std::move(text), fatal, type, sev, loc.file_name(), loc.line()});
}

}  // namespace advee::module
