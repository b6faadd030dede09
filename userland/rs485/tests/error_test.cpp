// SPDX-License-Identifier: GPL-2.0
#include "advee/rs485/error.hpp"

#include <gtest/gtest.h>

namespace advee::rs485 {
namespace {

TEST(Rs485Error, CategoryNamesEveryOutcomeOfTheSpec) {
  EXPECT_STREQ(rs485_category().name(), "rs485");
  const std::pair<Outcome, std::string_view> names[] = {
      {Outcome::ok, "OK"},         {Outcome::timeout, "TIMEOUT"},   {Outcome::bad_crc, "BADCRC"},
      {Outcome::unknown_instruction, "UNKINSTR"}, {Outcome::device_error, "DEVERR"},
      {Outcome::error, "ERROR"},   {Outcome::bad_response, "BADRESP"}};
  for (auto [o, name] : names) {
    EXPECT_EQ(outcome_name(o), name);
    // The message starts with the spec's name so logs can be grepped for it.
    EXPECT_EQ(make_error_code(o).message().rfind(std::string(name), 0), 0u) << make_error_code(o).message();
  }
}

TEST(Rs485Error, OkIsNoErrorAndFailuresAreProtocolOutcomes) {
  EXPECT_FALSE(make_error_code(Outcome::ok));
  EXPECT_FALSE(is_protocol_outcome(make_error_code(Outcome::ok)));
  std::error_code ec = Outcome::timeout;  // is_error_code_enum
  EXPECT_TRUE(ec);
  EXPECT_TRUE(is_protocol_outcome(ec));
  EXPECT_EQ(ec, Outcome::timeout);
  EXPECT_NE(ec, Outcome::bad_crc);
  EXPECT_FALSE(is_protocol_outcome(std::make_error_code(std::errc::io_error)));
}

TEST(Rs485Error, UnknownValueHasAMessageNotACrash) {
  const std::error_code ec(42, rs485_category());
  EXPECT_NE(ec.message().find("42"), std::string::npos);
}

TEST(Rs485Expected, ValueOrErrorAndValueThrowsOnError) {
  Expected<int> good = 7;
  ASSERT_TRUE(good);
  EXPECT_EQ(*good, 7);
  EXPECT_FALSE(good.error());
  Expected<int> bad = Outcome::device_error;
  EXPECT_FALSE(bad);
  EXPECT_EQ(bad.error(), Outcome::device_error);
  EXPECT_THROW((void)bad.value(), std::system_error);
}

}  // namespace
}  // namespace advee::rs485
