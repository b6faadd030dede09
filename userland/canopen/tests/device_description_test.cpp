// SPDX-License-Identifier: GPL-2.0
// EDS/DCF (CiA 306): parsing into the ObjectDictionary model, parse errors
// with file:line, truncated and garbled input, DCF write round trips.
#include <gtest/gtest.h>

#include <cstring>
#include <random>

#include "advee/canopen/device_description.hpp"

namespace advee::canopen {
namespace {

// Covers: comments, case-insensitive keys and sections, the three lists,
// VAR, RECORD, compact ARRAY with [XXXXValue]/[XXXXName], $NODEID in both
// orders, hexadecimal, octal, decimal and negative numbers, a string, a
// domain, limits, a REAL32.
constexpr std::string_view kEds = R"(; test device
[FileInfo]
FileName=test.eds
FileVersion=1
CreatedBy=advee

[DeviceInfo]
VendorName=Advee
VendorNumber=0x000000FB
ProductNumber=0x64200000
RevisionNumber=0x00010000

[DummyUsage]
Dummy0002=0

[MandatoryObjects]
SupportedObjects=3
1=0x1000
2=0x1001
3=0x1018

[OptionalObjects]
SupportedObjects=4
1=0x1008
2=0x1400
3=0x1F80
4=0x6502

[ManufacturerObjects]
SupportedObjects=3
1=0x2000
2=0x2001
3=0x2100

[1000]
ParameterName=Device type
ObjectType=0x7
DataType=0x0007
AccessType=ro
DefaultValue=0x00020192
PDOMapping=0

[1001]
ParameterName=Error register
objecttype=7
DataType=5
AccessType=ro
DefaultValue=0
PDOMapping=1

[1008]
ParameterName=Manufacturer device name
ObjectType=0x7
DataType=0x0009
AccessType=const
DefaultValue=Test drive 1

[1018]
ParameterName=Identity object
ObjectType=0x9
SubNumber=5

[1018sub0]
ParameterName=Number of entries
DataType=0x0005
AccessType=ro
DefaultValue=4

[1018sub1]
ParameterName=Vendor-ID
DataType=0x0007
AccessType=ro
DefaultValue=0x000000FB

[1018sub2]
ParameterName=Product code
DataType=0x0007
AccessType=ro
DefaultValue=0x64200000

[1018sub3]
ParameterName=Revision number
DataType=0x0007
AccessType=ro
DefaultValue=0x00010000

[1018SUB4]
ParameterName=Serial number
DataType=0x0007
AccessType=ro
DefaultValue=$NODEID

[1400]
ParameterName=RPDO1 communication
ObjectType=0x9
SubNumber=3

[1400sub0]
ParameterName=Highest sub-index
DataType=0x0005
AccessType=ro
DefaultValue=2

[1400sub1]
ParameterName=COB-ID
DataType=0x0007
AccessType=rw
DefaultValue=$NODEID+0x200

[1400sub2]
ParameterName=Transmission type
DataType=0x0005
AccessType=rw
DefaultValue=255

[1f80]
ParameterName=NMT startup
ObjectType=0x7
DataType=0x0007
AccessType=rw
DefaultValue=0x80000000+$NODEID

[2000]
ParameterName=Scratch
ObjectType=0x2
AccessType=rw
DefaultValue=0102FF

[2001]
ParameterName=Signed
ObjectType=0x7
DataType=0x0003
AccessType=rww
DefaultValue=-2
LowLimit=-100
HighLimit=0x64
PDOMapping=1

[2100]
ParameterName=Gains
ObjectType=0x8
DataType=0x0008
AccessType=rw
CompactSubObj=3

[2100Value]
NrOfEntries=2
1=1.5
3=-0.25

[2100Name]
NrOfEntries=1
2=Middle gain

[6502]
ParameterName=Supported drive modes
ObjectType=0x7
DataType=0x0007
AccessType=ro
DefaultValue=045
)";

DeviceDescription parse_ok(std::string_view text, std::optional<std::uint8_t> node = std::nullopt) {
  DescriptionResult r = parse_device_description(text, "test.eds", node);
  for (const auto& e : r.errors) ADD_FAILURE() << e.text();
  EXPECT_TRUE(r.description);
  return r.description ? std::move(*r.description) : DeviceDescription{};
}

TEST(DeviceDescriptionTest, ReadsObjectsValuesAndTexts) {
  const DeviceDescription d = parse_ok(kEds, 5);
  EXPECT_FALSE(d.is_dcf());
  EXPECT_EQ(d.node_id, 5);
  EXPECT_EQ(DeviceDescription::value(d.device_info, "vendornumber"), "0x000000FB");
  const ObjectDictionary& od = d.od;
  EXPECT_EQ(od.get<std::uint32_t>(0x1000), 0x00020192u);
  EXPECT_EQ(od.find(0x1000, 0)->access, Access::kReadOnly);
  EXPECT_TRUE(od.find(0x1001, 0)->mappable);
  EXPECT_EQ(od.find(0x1001, 0)->value.size(), 1u);
  const OdEntry* name = od.find(0x1008, 0);
  ASSERT_NE(name, nullptr);
  EXPECT_EQ(std::string(name->value.begin(), name->value.end()), "Test drive 1");
  EXPECT_TRUE(name->variable_size);
  EXPECT_EQ(name->access, Access::kReadOnly);
  EXPECT_EQ(od.get<std::uint32_t>(0x1018, 4), 5u);
  EXPECT_EQ(od.find(0x1018, 4)->default_text, "$NODEID");
  EXPECT_EQ(od.object(0x1018)->object_type, 9);
  EXPECT_EQ(od.object(0x1018)->name, "Identity object");
  EXPECT_EQ(od.get<std::uint32_t>(0x1400, 1), 0x205u);
  EXPECT_EQ(od.get<std::uint32_t>(0x1F80), 0x80000005u);
  EXPECT_EQ(od.find(0x2000, 0)->value, (std::vector<std::uint8_t>{0x01, 0x02, 0xFF}));
  EXPECT_EQ(od.find(0x2000, 0)->data_type, 0x000F);
  EXPECT_EQ(od.get<std::int16_t>(0x2001), -2);
  EXPECT_EQ(od.find(0x2001, 0)->high_limit, "0x64");
  EXPECT_EQ(od.get<std::uint8_t>(0x2100, 0), 3);
  auto real = [&od](std::uint8_t sub) {
    const auto bits = od.get<std::uint32_t>(0x2100, sub);
    float f;
    std::memcpy(&f, &bits, sizeof f);
    return f;
  };
  EXPECT_EQ(real(1), 1.5f);
  EXPECT_EQ(real(2), 0.0f);
  EXPECT_EQ(real(3), -0.25f);
  EXPECT_EQ(od.find(0x2100, 1)->name, "Gains1");
  EXPECT_EQ(od.find(0x2100, 2)->name, "Middle gain");
  EXPECT_EQ(od.get<std::uint32_t>(0x6502), 045u);  // octal
}

TEST(DeviceDescriptionTest, EdsWithoutNodeIdEvaluatesNodeIdAsZero) {
  const DeviceDescription d = parse_ok(kEds);
  EXPECT_EQ(d.node_id, 0);
  EXPECT_EQ(d.od.get<std::uint32_t>(0x1400, 1), 0x200u);
}

std::string as_dcf(std::string_view eds, std::string_view commissioning, std::string_view extra_key,
                   std::string_view after_section) {
  std::string s(eds);
  s += "\n[DeviceComissioning]\n";
  s += commissioning;
  const auto at = s.find(after_section);
  const auto eol = s.find('\n', at + after_section.size());
  s.insert(eol + 1, std::string(extra_key) + "\n");
  return s;
}

TEST(DeviceDescriptionTest, DcfParameterValueIsTheValueAndNodeIdComesFromCommissioning) {
  const std::string dcf = as_dcf(kEds, "NodeID=0x22\nNodeName=left\nBaudrate=1000\n", "ParameterValue=$NODEID+0x300",
                                 "[1400sub1]");
  const DeviceDescription d = parse_ok(dcf);
  EXPECT_TRUE(d.is_dcf());
  EXPECT_EQ(d.node_id, 0x22);
  const OdEntry* cob = d.od.find(0x1400, 1);
  EXPECT_EQ(cob->parameter_text, "$NODEID+0x300");
  EXPECT_EQ(d.od.get<std::uint32_t>(0x1400, 1), 0x322u);
  EXPECT_EQ(d.od.get<std::uint32_t>(0x1018, 4), 0x22u);
}

TEST(DeviceDescriptionTest, WrittenDcfParsesToTheSameModel) {
  for (const std::string& text : {std::string(kEds), as_dcf(kEds, "NodeID=3\n", "ParameterValue=-7", "[2001]")}) {
    const DeviceDescription a = parse_ok(text, 3);
    const std::string written = write_dcf(a);
    const DeviceDescription b = parse_ok(written, 3);
    EXPECT_TRUE(same_model(a, b)) << written;
    // And the writer is stable: writing the re-read model gives the same text.
    EXPECT_EQ(write_dcf(b), written);
  }
}

TEST(DeviceDescriptionTest, CodeBuiltDictionaryWritesAndReadsBack) {
  DeviceDescription d;
  d.file_info = {{"FileName", "code.dcf"}};
  d.od.add<std::uint32_t>(0x1000, 0, 0x192, Access::kReadOnly);
  d.od.add<std::uint16_t>(0x1017, 0, 100);
  d.od.add_string(0x1008, 0, "name");
  DescriptionResult r = parse_device_description(write_dcf(d), "code.dcf");
  ASSERT_TRUE(r.description) << (r.errors.empty() ? "" : r.errors[0].text());
  EXPECT_EQ(r.description->od.get<std::uint32_t>(0x1000), 0x192u);
  EXPECT_EQ(r.description->od.get<std::uint16_t>(0x1017), 100u);
  EXPECT_EQ(r.description->od.find(0x1017, 0)->access, Access::kReadWrite);
}

struct BadCase {
  std::string from, to;  // replace in kEds
  std::string at;        // the line the error points at ("": the list or file)
  std::string expected;  // part of the message
};

unsigned line_of(std::string_view text, std::string_view what) {
  const auto at = text.find(what);
  return static_cast<unsigned>(std::count(text.begin(), text.begin() + static_cast<std::ptrdiff_t>(at), '\n') + 1);
}

TEST(DeviceDescriptionTest, ErrorsSayFileLineAndWhatWasExpected) {
  const std::vector<BadCase> cases = {
      {"DataType=0x0005\nAccessType=ro\nDefaultValue=4", "DataType=0x0005\nAccessType=ro\nDefaultValue=400",
       "DefaultValue=400", "within the range of UNSIGNED8 (0..255), found '400'"},
      {"DefaultValue=$NODEID+0x200", "DefaultValue=$NODE+0x200", "DefaultValue=$NODE+0x200", "expected a number"},
      {"AccessType=rww", "AccessType=readwrite", "AccessType=readwrite",
       "expected AccessType ro, wo, rw, rwr, rww or const"},
      {"DataType=0x0003", "DataType=0x00FF", "DataType=0x00FF", "expected a CiA 301 data type"},
      {"SubNumber=5", "SubNumber=6", "SubNumber=6", "expected SubNumber=6 sub-object sections [1018subN], found 5"},
      {"4=0x6502\n", "", "[OptionalObjects]", "expected 4=<index> in [OptionalObjects]"},
      {"3=0x2100", "3=0x2101", "3=0x2101", "expected a section [2101] for object 0x2101, listed here"},
      {"3=0x2100", "3=0x1000", "3=0x1000", "expected each object in one list once; 0x1000 is also at line"},
      {"CreatedBy=advee", "CreatedBy advee", "CreatedBy advee",
       "expected '[section]' or 'key=value', found 'CreatedBy advee'"},
      {"[DummyUsage]", "[DummyUsage", "[DummyUsage", "expected a section header '[name]'"},
      {"[1001]\nParameterName=Error register", "[1001]\nParameterName=Error register\nDataType=7", "DataType=5",
       "expected each key once in [1001]; DataType is already at line"},
      {"PDOMapping=1\n\n[2100]", "PDOMapping=2\n\n[2100]", "PDOMapping=2", "expected PDOMapping 0 or 1"},
      {"DefaultValue=0102FF", "DefaultValue=0102F", "DefaultValue=0102F", "expected hexadecimal bytes"},
      {"DefaultValue=0x00020192", "DefaultValue=0x1000000000000000000", "DefaultValue=0x1000000000000000000",
       "(above 64 bits)"},
      {"CompactSubObj=3", "CompactSubObj=0", "CompactSubObj=0", "expected CompactSubObj 1..254"},
      {"DefaultValue=0x80000000+$NODEID", "DefaultValue=0x7FFFFFFFFFFFFFFF+1+$NODEID",
       "DefaultValue=0x7FFFFFFFFFFFFFFF+1+$NODEID", "within 64 bits"},
      {"DefaultValue=-2", "DefaultValue=-0x8000000000000000", "DefaultValue=-0x8000000000000000",
       "within the range of INTEGER16"},
      {"[1f80]\nParameterName=NMT startup\n", "[1f80]\n", "[1f80]", "expected ParameterName=<name> in [1f80]"},
  };
  for (const BadCase& c : cases) {
    std::string text(kEds);
    const auto at = text.find(c.from);
    ASSERT_NE(at, std::string::npos) << c.from;
    text.replace(at, c.from.size(), c.to);
    const DescriptionResult r = parse_device_description(text, "bad.eds");
    ASSERT_FALSE(r.errors.empty()) << c.to;
    EXPECT_FALSE(r.description);
    const DescriptionError& e = r.errors.front();
    EXPECT_NE(e.message.find(c.expected), std::string::npos) << e.text();
    EXPECT_EQ(e.text().rfind("bad.eds:", 0), 0u) << e.text();
    if (!c.at.empty()) {
      EXPECT_EQ(e.line, line_of(text, c.at)) << e.text();
    }
  }
}

TEST(DeviceDescriptionTest, DuplicateSectionAndMissingFile) {
  const std::string dup = std::string(kEds) + "\n[1000]\nParameterName=again\n";
  const DescriptionResult r = parse_device_description(dup, "dup.eds");
  ASSERT_FALSE(r.errors.empty());
  EXPECT_NE(r.errors[0].text().find("dup.eds:" + std::to_string(line_of(dup, "[1000]\nParameterName=again"))),
            std::string::npos)
      << r.errors[0].text();
  EXPECT_NE(r.errors[0].message.find("is already at line " + std::to_string(line_of(dup, "[1000]"))), std::string::npos);
  const DescriptionResult m = load_device_description("/nonexistent/x.eds");
  ASSERT_EQ(m.errors.size(), 1u);
  EXPECT_EQ(m.errors[0].text().rfind("/nonexistent/x.eds: expected a readable file", 0), 0u) << m.errors[0].text();
  const DescriptionResult empty = parse_device_description("", "empty.eds");
  ASSERT_EQ(empty.errors.size(), 1u);
  EXPECT_NE(empty.errors[0].message.find("expected objects"), std::string::npos);
}

// Every prefix of the file (a truncated download) and files with random
// bytes overwritten: never a crash, and either a model or errors whose lines
// lie inside the text.
TEST(DeviceDescriptionTest, TruncatedAndGarbledInputNeverCrashes) {
  const std::string full(kEds);
  const auto lines = static_cast<unsigned>(std::count(full.begin(), full.end(), '\n') + 1);
  auto check = [lines](const std::string& text) {
    const DescriptionResult r = parse_device_description(text, "g.eds");
    EXPECT_NE(r.description.has_value(), !r.errors.empty());
    EXPECT_LE(r.errors.size(), kMaxDescriptionErrors);
    for (const auto& e : r.errors) EXPECT_LE(e.line, lines) << e.text();
  };
  for (std::size_t n = 0; n < full.size(); n += 7) check(full.substr(0, n));
  std::mt19937 rng(23);
  for (int round = 0; round < 300; ++round) {
    std::string g = full;
    for (int k = 0; k < 1 + round % 20; ++k)
      g[rng() % g.size()] = static_cast<char>(rng() % 256);
    check(g);
  }
  check(std::string(5000, '\xff'));
  check(std::string(5000, '['));
}

}  // namespace
}  // namespace advee::canopen
