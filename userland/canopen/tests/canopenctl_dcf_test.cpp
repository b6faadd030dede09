// SPDX-License-Identifier: GPL-2.0
// advee-canopenctl dcf's checks with no I/O: the node evaluates $NODEID, the
// DCF's NodeName names the node, the identity to check comes from the file,
// a concise DCF is told from text and carries no identity.
#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>

#include "advee/canopen/concise_dcf.hpp"
#include "advee/canopen/sim/drive_sim.hpp"
#include "canopenctl_dcf.hpp"
#include "canopenctl_text.hpp"

namespace advee::canopen::ctl {
namespace {

class CanopenctlDcfTest : public testing::Test {
 protected:
  std::filesystem::path dir =
      std::filesystem::temp_directory_path() / ("canopenctl-dcf-unit-" + std::to_string(::getpid()));
  void SetUp() override { std::filesystem::create_directories(dir); }
  void TearDown() override { std::filesystem::remove_all(dir); }
  std::string file(const std::string& name, const std::string& content) {
    const auto p = dir / name;
    std::ofstream(p, std::ios::binary) << content;
    return p.string();
  }
};

TEST_F(CanopenctlDcfTest, ADcfGivesTheIdentityTheNameAndTheDownloadsForThisNode) {
  std::string t(sim::shipped_eds(sim::DriveProfile::kIcla));
  t.insert(t.find("\n\n", t.find("[1800sub1]\n")) + 1, "ParameterValue=$NODEID+0x180\n");
  t += "\n[DeviceComissioning]\nNodeID=2\nNodeName=steering\n";
  DcfArgs a;
  a.node = "5";
  a.file = file("icla.dcf", t);
  const DcfCommand c = check_dcf("dcf download", a);
  EXPECT_FALSE(c.concise_input);
  EXPECT_EQ(c.boot.node, 5);
  EXPECT_EQ(c.boot.name, "steering");
  ASSERT_TRUE(c.boot.identity[1]);
  ASSERT_FALSE(c.boot.configuration.empty());
  EXPECT_EQ(c.boot.configuration.back(), SdoWrite::of<std::uint32_t>(0x1800, 1, 0x185)) << "$NODEID is the command's node";
  EXPECT_TRUE(c.boot.start);
  EXPECT_EQ(describe_download(c, 0).rfind("node 5 (steering): ", 0), 0u) << describe_download(c, 0);
  EXPECT_NE(describe_download(c, 0).find("identity checked (device type 0x"), std::string::npos);
  a.no_start = true;
  EXPECT_FALSE(check_dcf("dcf download", a).boot.start);
}

TEST_F(CanopenctlDcfTest, AConciseDcfIsDownloadedWithoutIdentity) {
  const auto bytes = write_concise_dcf({SdoWrite::of<std::uint16_t>(0x1017, 0, 100)});
  DcfArgs a;
  a.node = "3";
  a.file = file("n3.cdcf", std::string(bytes.begin(), bytes.end()));
  const DcfCommand c = check_dcf("dcf download", a);
  EXPECT_TRUE(c.concise_input);
  EXPECT_EQ(c.boot.configuration.size(), 1u);
  for (const auto& id : c.boot.identity) EXPECT_FALSE(id);
  EXPECT_EQ(describe_download(c, 2),
            "node 3 (n3.cdcf): 1 object written, identity not checked (a concise DCF has none), "
            "2 timed-out transfers repeated, started");
  EXPECT_THROW(check_dcf("dcf concise", a), UsageError);
  a.node = "0";
  EXPECT_THROW(check_dcf("dcf download", a), UsageError);
}

}  // namespace
}  // namespace advee::canopen::ctl
