// SPDX-License-Identifier: GPL-2.0
// advee-canopenctl's argument checks and the monitor's frame descriptions (no I/O).
#include "canopenctl_text.hpp"

#include <gtest/gtest.h>

namespace advee::canopen::ctl {
namespace {

TEST(CanopenctlTextTest, MonitorNamesRpdosAndTpdosByTheirCobId) {
  EXPECT_EQ(describe_frame(make_frame(0x181, {0x37, 0x02})), "181#3702  TPDO1 node 1");
  EXPECT_EQ(describe_frame(make_frame(0x201, {0x0F, 0x00})), "201#0F00  RPDO1 node 1");
  EXPECT_EQ(describe_frame(make_frame(0x302, {0x0F})), "302#0F  RPDO2 node 2");
  EXPECT_EQ(describe_frame(make_frame(0x383, {0x0F})), "383#0F  TPDO3 node 3");
  EXPECT_EQ(describe_frame(make_frame(0x4FF, {0x0F})), "4FF#0F  TPDO4 node 127");
  EXPECT_EQ(describe_frame(make_frame(0x501, {0x0F})), "501#0F  RPDO4 node 1");
  EXPECT_EQ(describe_frame(make_frame(0x705, {0x05})), "705#05  heartbeat node 5 operational");
  EXPECT_EQ(describe_frame(make_frame(0x000, {0x01, 0x05})), "000#0105  NMT start node 5");
}

TEST(CanopenctlTextTest, ValuesMustFitTheirType) {
  EXPECT_THROW(encode(parse_type("i8"), "300"), UsageError) << "i8 300 would send 0x2C";
  EXPECT_THROW(encode(parse_type("i8"), "-129"), UsageError);
  EXPECT_THROW(encode(parse_type("u8"), "256"), UsageError);
  EXPECT_THROW(encode(parse_type("u16"), "-1"), UsageError) << "no wrap to 0xFFFF";
  EXPECT_THROW(encode(parse_type("u32"), "12abc"), UsageError);
  EXPECT_THROW(encode(parse_type("hex"), "ABC"), UsageError);
  EXPECT_THROW(encode(parse_type("hex"), "0x12"), UsageError);
  EXPECT_EQ(encode(parse_type("i8"), "-128"), std::vector<std::uint8_t>{0x80});
  EXPECT_EQ(encode(parse_type("i16"), "-2"), (std::vector<std::uint8_t>{0xFE, 0xFF}));
  EXPECT_EQ(encode(parse_type("u32"), "0x12345678"), (std::vector<std::uint8_t>{0x78, 0x56, 0x34, 0x12}));
  EXPECT_EQ(encode(parse_type("u64"), "18446744073709551615"), std::vector<std::uint8_t>(8, 0xFF));
  EXPECT_EQ(encode(parse_type("i64"), "-1"), std::vector<std::uint8_t>(8, 0xFF));
  EXPECT_EQ(encode(parse_type("hex"), "0aFF"), (std::vector<std::uint8_t>{0x0A, 0xFF}));
  EXPECT_EQ(encode(parse_type("str"), ""), std::vector<std::uint8_t>{});
}

TEST(CanopenctlTextTest, NodesObjectsAndTypesAreChecked) {
  EXPECT_EQ(parse_node("127"), 127);
  EXPECT_EQ(parse_node("all", true), 0);
  EXPECT_THROW(parse_node("all"), UsageError);
  EXPECT_THROW(parse_node("0"), UsageError);
  EXPECT_THROW(parse_node("128"), UsageError);
  EXPECT_THROW(parse_node("1x"), UsageError);
  EXPECT_EQ(parse_object("6040"), std::make_pair(std::uint16_t{0x6040}, std::uint8_t{0}));
  EXPECT_EQ(parse_object("1018:4"), std::make_pair(std::uint16_t{0x1018}, std::uint8_t{4}));
  EXPECT_THROW(parse_object("10000"), UsageError);
  EXPECT_THROW(parse_object("1018:256"), UsageError);
  EXPECT_THROW(parse_object("1018:"), UsageError);
  EXPECT_THROW(parse_type("u33"), UsageError);
}

TEST(CanopenctlTextTest, NodeRangesAreChecked) {
  EXPECT_EQ(parse_node_range("1-127"), std::make_pair(std::uint8_t{1}, std::uint8_t{127}));
  EXPECT_EQ(parse_node_range("5"), std::make_pair(std::uint8_t{5}, std::uint8_t{5}));
  for (const char* bad : {"0-5", "1-128", "9-3", "1-", "-5", "a-b", "0", "1-2-3"})
    EXPECT_THROW(parse_node_range(bad), UsageError) << bad;
}

TEST(CanopenctlTextTest, PdoRemapArgumentsAreChecked) {
  const PdoMapping m = parse_pdo_remap(3, "tpdo", "4", {"6041:0/16", "6064:00/32"});
  EXPECT_EQ(to_string(m), "TPDO4 0x483 type 255: 6041:00/16 6064:00/32");
  EXPECT_EQ(to_string(parse_pdo_remap(1, "rpdo", "1", {})), "RPDO1 0x201 type 255:");
  const std::vector<std::vector<std::string>> bad_entries = {
      {"6041:0"}, {"6041:0/0"}, {"6041:0/65"}, {"6041:0:1/16"}, {"6041:0/16x"},
      {"6064:0/32", "6064:0/32", "6041:0/16"}, std::vector<std::string>(9, "6041:0/1")};
  for (const auto& e : bad_entries) EXPECT_THROW(parse_pdo_remap(3, "tpdo", "1", e), UsageError) << e[0];
  EXPECT_THROW(parse_pdo_remap(3, "xpdo", "1", {}), UsageError);
  EXPECT_THROW(parse_pdo_remap(3, "tpdo", "0", {}), UsageError);
  EXPECT_THROW(parse_pdo_remap(3, "tpdo", "5", {}), UsageError);
}

TEST(CanopenctlTextTest, HeartbeatsAndIdentities) {
  EXPECT_EQ(describe_heartbeat(make_frame(0x703, {0x00})), "heartbeat node 3 boot-up");
  EXPECT_EQ(describe_heartbeat(make_frame(0x77F, {0x7F})), "heartbeat node 127 pre-operational");
  EXPECT_EQ(describe_heartbeat(make_frame(0x703, {0x00, 0x00})), std::nullopt) << "not one byte";
  EXPECT_EQ(describe_heartbeat(make_frame(0x603, {0x05})), std::nullopt);
  Identity id;
  id.device_type = 0x20192;
  id.identity = {0xFB, 0x64200000, std::nullopt, 3};
  EXPECT_EQ(describe_identity(3, id),
            "node 3: device type 0x00020192, vendor 0x000000FB, product 0x64200000, revision -, serial 0x00000003");
}

TEST(CanopenctlTextTest, FormatReadsBackWhatEncodeWrote) {
  for (const char* v : {"-128", "127", "0"}) EXPECT_EQ(format(parse_type("i8"), encode(parse_type("i8"), v)), v);
  EXPECT_EQ(format(parse_type("i32"), encode(parse_type("i32"), "-70000")), "-70000");
  EXPECT_EQ(format(parse_type("u16"), encode(parse_type("u16"), "1234")), "1234 (0x4D2)");
  EXPECT_EQ(format(parse_type("u16"), {1, 2, 3}), "010203") << "wrong length: hex";
}

}  // namespace
}  // namespace advee::canopen::ctl
