// SPDX-License-Identifier: GPL-2.0
// The reporter prints from the print threshold up, publishes common.error_t
// from the send threshold up (memq:// LCM, in-process) and logs everything.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <lcm/lcm-cpp.hpp>
#include <sstream>
#include <vector>

#include "advee/module/subscription.hpp"
#include "advee/module/error.hpp"
#include "common/error_t.hpp"

using namespace advee::module;

namespace {

struct Received {
  std::vector<common::error_t> msgs;
};

TEST(ErrorReporter, ThresholdsForPrintingAndSending) {
  lcm::LCM lcm("memq://");
  ASSERT_TRUE(lcm.good());
  Received rx;
  Subscription<common::error_t> sub(lcm, "CM_DATA_ERROR", [&](const common::error_t& m) { rx.msgs.push_back(m); });
  ErrorReporter::Config cfg;
  cfg.print_severity = static_cast<std::int8_t>(Severity::Warning);
  cfg.send_severity = static_cast<std::int8_t>(Severity::Error);
  ErrorReporter r("driver_x", cfg, &lcm);

  testing::internal::CaptureStderr();
  r.report(Severity::Notice, ErrorType::Unknown, 0, "just so you know");
  r.report(Severity::Warning, ErrorType::Timeout, 110, "SD1 did not answer");
  const int line = __LINE__ + 1;
  r.report(Severity::Error, ErrorType::Device, 5, "bus dead", true);
  const std::string printed = testing::internal::GetCapturedStderr();
  while (lcm.handleTimeout(0) > 0) {
  }

  EXPECT_EQ(printed.find("just so you know"), std::string::npos);
  EXPECT_NE(printed.find("driver_x: warning: SD1 did not answer [timeout 110"), std::string::npos)
      << printed;
  EXPECT_NE(printed.find("driver_x: error (fatal): bus dead [device 5, error_test.cpp:" +
                         std::to_string(line) + "]"),
            std::string::npos)
      << printed;

  ASSERT_EQ(rx.msgs.size(), 1u);
  const auto& m = rx.msgs[0];
  EXPECT_EQ(m.module, "driver_x");
  EXPECT_EQ(m.text, "bus dead");
  EXPECT_EQ(m.number, 5);
  EXPECT_TRUE(m.fatal);
  EXPECT_EQ(m.type, common::error_t::TYPE_DEVICE);
  EXPECT_EQ(m.severity, common::error_t::SEVERITY_ERROR);
  EXPECT_EQ(m.line, line);
  EXPECT_NE(m.file.find("error_test.cpp"), std::string::npos);
  EXPECT_GT(m.utime, 1'600'000'000'000'000);
}

TEST(ErrorReporter, NoneSilencesAndTheLogKeepsEverything) {
  lcm::LCM lcm("memq://");
  Received rx;
  Subscription<common::error_t> sub(lcm, "ERRS", [&](const common::error_t& m) { rx.msgs.push_back(m); });
  ErrorReporter::Config cfg{kSeverityNone, kSeverityNone, "ERRS"};
  ErrorReporter r("m", cfg, &lcm);
  const auto log = std::filesystem::temp_directory_path() /
                   ("advee-error-test-" + std::to_string(::getpid()) + ".log");
  r.set_log_file(log.string());
  testing::internal::CaptureStderr();
  r.report(Severity::Error, ErrorType::Resource, 12, "out of memory");
  r.report(Severity::Notice, ErrorType::Unknown, 0, "hello");
  EXPECT_EQ(testing::internal::GetCapturedStderr(), "");
  while (lcm.handleTimeout(0) > 0) {
  }
  EXPECT_TRUE(rx.msgs.empty());
  std::ifstream in(log);
  std::stringstream ss;
  ss << in.rdbuf();
  EXPECT_NE(ss.str().find("m: error: out of memory"), std::string::npos);
  EXPECT_NE(ss.str().find("m: notice: hello"), std::string::npos);
  std::filesystem::remove(log);
}

TEST(ErrorReporter, SeverityNames) {
  EXPECT_EQ(parse_severity("Warning"), Severity::Warning);
  EXPECT_EQ(parse_severity("error"), Severity::Error);
  EXPECT_FALSE(parse_severity("fatal"));
}

}  // namespace
