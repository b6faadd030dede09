// SPDX-License-Identifier: GPL-2.0
// advee-rs485ctl's argument parsing: bad input is a UsageError naming it, never a crash.
#include "../tools/cli_parse.hpp"

#include <gtest/gtest.h>

namespace advee::rs485::cli {
namespace {

using Bytes = std::vector<std::uint8_t>;

TEST(Rs485ctlParse, Addresses) {
  EXPECT_EQ(parse_address("0x10"), 0x10);
  EXPECT_EQ(parse_address("16"), 16);
  EXPECT_EQ(parse_address("0xfe"), 0xFE);
  EXPECT_EQ(parse_address("0xff", true), 0xFF);
  EXPECT_THROW(parse_address("0xff"), UsageError);
  EXPECT_THROW(parse_address("0x100", true), UsageError);
  EXPECT_THROW(parse_address(""), UsageError);
  EXPECT_THROW(parse_address("-1"), UsageError);
  EXPECT_THROW(parse_address("12abc"), UsageError);
  EXPECT_THROW(parse_address("99999999999999999999999"), UsageError);
  try {
    parse_address("0x1ff");
    FAIL();
  } catch (const UsageError& e) {
    EXPECT_NE(std::string(e.what()).find("0x1ff"), std::string::npos) << e.what();
  }
}

TEST(Rs485ctlParse, HexDataInEveryAcceptedSpelling) {
  EXPECT_EQ(parse_hex_bytes({"01", "02", "ff"}), (Bytes{1, 2, 0xFF}));
  EXPECT_EQ(parse_hex_bytes({"0102ff"}), (Bytes{1, 2, 0xFF}));
  EXPECT_EQ(parse_hex_bytes({"0x01,0x02"}), (Bytes{1, 2}));
  EXPECT_EQ(parse_hex_bytes({"de:ad"}), (Bytes{0xDE, 0xAD}));
  EXPECT_EQ(parse_hex_bytes({"DE AD"}), (Bytes{0xDE, 0xAD}));
  EXPECT_EQ(parse_hex_bytes({}), Bytes{});
}

TEST(Rs485ctlParse, BadHexDataIsAUsageError) {
  EXPECT_THROW(parse_hex_bytes({"zz"}), UsageError);
  EXPECT_THROW(parse_hex_bytes({"123"}), UsageError);
  EXPECT_THROW(parse_hex_bytes({"1,2"}), UsageError);
  EXPECT_THROW(parse_hex_bytes({std::string(512, 'a')}), UsageError);  // 256 bytes
  EXPECT_EQ(parse_hex_bytes({std::string(510, 'a')}).size(), 255u);
}

TEST(Rs485ctlParse, Durations) {
  using std::chrono::microseconds;
  EXPECT_EQ(parse_duration("10"), microseconds(10000));
  EXPECT_EQ(parse_duration("10ms"), microseconds(10000));
  EXPECT_EQ(parse_duration("500us"), microseconds(500));
  EXPECT_EQ(parse_duration("1.5ms"), microseconds(1500));
  EXPECT_EQ(parse_duration("2s"), microseconds(2000000));
  for (const char* bad : {"", "ms", "10 ms", "10h", "-1ms", "1e3", "1.2.3", "99999999999999s"})
    EXPECT_THROW(parse_duration(bad), UsageError) << bad;
}

TEST(Rs485ctlParse, HexOutput) {
  EXPECT_EQ(hex({}), "");
  EXPECT_EQ(hex({0x00, 0xAB, 0x10}), "00 ab 10");
}

}  // namespace
}  // namespace advee::rs485::cli
