// SPDX-License-Identifier: GPL-2.0
// The shipped EDS files of the simulated drives (userland/canopen/data): they
// parse, their [DeviceInfo] agrees with their 0x1018, they survive a DCF
// round trip, and a simulated drive built from another file reports that
// file's identity or its parse errors.
#include <gtest/gtest.h>

#include <cstdio>
#include <fstream>

#include "advee/canopen/device_description.hpp"
#include "advee/canopen/sim/drive_sim.hpp"

namespace advee::canopen::sim {
namespace {

TEST(ShippedEdsTest, ParseAgreeWithDeviceInfoAndRoundTrip) {
  for (DriveProfile p : {DriveProfile::kEpos, DriveProfile::kIcla}) {
    DescriptionResult r = parse_device_description(shipped_eds(p), shipped_eds_name(p), 9);
    for (const auto& e : r.errors) ADD_FAILURE() << e.text();
    ASSERT_TRUE(r.description);
    const DeviceDescription& d = *r.description;
    auto info = [&d](const char* key) {
      return std::strtoul(DeviceDescription::value(d.device_info, key).value_or("-1").c_str(), nullptr, 0);
    };
    EXPECT_EQ(info("VendorNumber"), d.od.get<std::uint32_t>(0x1018, 1)) << shipped_eds_name(p);
    EXPECT_EQ(info("ProductNumber"), d.od.get<std::uint32_t>(0x1018, 2)) << shipped_eds_name(p);
    EXPECT_EQ(info("RevisionNumber"), d.od.get<std::uint32_t>(0x1018, 3)) << shipped_eds_name(p);
    EXPECT_EQ(d.od.get<std::uint32_t>(0x1018, 4), 9u);  // serial = node-ID ($NODEID)
    DescriptionResult again = parse_device_description(write_dcf(d), "written.dcf", 9);
    ASSERT_TRUE(again.description);
    EXPECT_TRUE(same_model(d, *again.description));
  }
}

TEST(ShippedEdsTest, SimulatedDriveTakesItsDictionaryFromTheGivenFile) {
  std::string text(shipped_eds(DriveProfile::kEpos));
  const auto at = text.find("DefaultValue=0x64200000");
  ASSERT_NE(at, std::string::npos);
  text.replace(at, 23, "DefaultValue=0x64200001");
  const std::string path = testing::TempDir() + "other-epos.eds";
  std::ofstream(path) << text;
  DriveSimConfig c;
  c.eds_file = path;
  SimulatedDrive d(c, [](const CanFrame&) {}, [] { return TimePoint{}; });
  EXPECT_EQ(d.od().get<std::uint32_t>(0x1018, 2), 0x64200001u);

  std::ofstream(path) << "[MandatoryObjects]\nSupportedObjects=1\n1=0x1000\n";
  try {
    SimulatedDrive bad(c, [](const CanFrame&) {}, [] { return TimePoint{}; });
    ADD_FAILURE() << "a bad description was accepted";
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find(path + ":3: expected a section [1000]"), std::string::npos) << e.what();
  }
  std::remove(path.c_str());
}

}  // namespace
}  // namespace advee::canopen::sim
