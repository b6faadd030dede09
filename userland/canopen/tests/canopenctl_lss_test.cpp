// SPDX-License-Identifier: GPL-2.0
// advee-canopenctl lss: argument checks and output text, no I/O.
#include <gtest/gtest.h>

#include "canopenctl_lss.hpp"
#include "canopenctl_text.hpp"

namespace advee::canopen::ctl {
namespace {

TEST(CanopenctlLssTest, IdentitiesAreFourHexWords) {
  EXPECT_EQ(parse_lss_address("FB:0x64200000:10000:1"), (LssAddress{{0xFB, 0x64200000, 0x10000, 1}}));
  EXPECT_EQ(parse_lss_address("ffffffff:0:0:0").vendor(), 0xFFFFFFFFu);
  for (const char* bad : {"", "1:2:3", "1:2:3:4:5", "1::3:4", "1:2:3:x", "1:2:3:123456789", "0x:1:2:3", "1:2:3:4:"})
    EXPECT_THROW(parse_lss_address(bad), UsageError) << bad;
}

TEST(CanopenctlLssTest, CommandsAreChecked) {
  LssArgs a;
  a.assign = "10";
  a.store = true;
  auto c = check_lss("lss scan", a);
  EXPECT_EQ(c.assign, 10);
  EXPECT_TRUE(c.store);
  EXPECT_EQ(c.config.timeout, std::chrono::milliseconds(100));
  a.vendor = "0xFB";
  a.product = "64200000";
  c = check_lss("lss scan", a);
  EXPECT_EQ(c.known[0], 0xFBu);
  EXPECT_EQ(c.known[1], 0x64200000u);
  EXPECT_FALSE(c.known[2]);
  a.vendor = "FBX";
  EXPECT_THROW(check_lss("lss scan", a), UsageError);
  a.vendor.clear();
  a.product = "123456789";
  EXPECT_THROW(check_lss("lss scan", a), UsageError);
  a.product.clear();
  a.assign.clear();
  EXPECT_THROW(check_lss("lss scan", a), UsageError) << "--store without --assign";
  a = {};
  a.assign = "128";
  EXPECT_THROW(check_lss("lss scan", a), UsageError);
  a = {};
  a.node = "0";
  EXPECT_THROW(check_lss("lss set-id", a), UsageError);
  a.node = "12";
  a.identity = "FB:64200000:10000:7";
  c = check_lss("lss set-id", a);
  EXPECT_EQ(c.node, 12);
  ASSERT_TRUE(c.identity);
  EXPECT_EQ(c.identity->serial(), 7u);
  a = {};
  a.settle_ms = a.answer_ms;
  EXPECT_THROW(check_lss("lss identify", a), UsageError) << "settle as long as the timeout";
}

TEST(CanopenctlLssTest, FoundNodesArePrintedWithTheirNodeId) {
  EXPECT_EQ(describe_found({{{0xFB, 0x64200000, 0x10000, 0x101}}, 10}),
            "vendor 0x000000FB product 0x64200000 revision 0x00010000 serial 0x00000101 node-ID 10");
  EXPECT_EQ(describe_found({{{1, 2, 3, 4}}, kLssUnconfigured}),
            "vendor 0x00000001 product 0x00000002 revision 0x00000003 serial 0x00000004");
}

}  // namespace
}  // namespace advee::canopen::ctl
