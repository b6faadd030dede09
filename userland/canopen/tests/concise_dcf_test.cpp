// SPDX-License-Identifier: GPL-2.0
// Concise DCF (CiA 302-3): byte layout, round trip, every cut and garbled
// input refused with its offset, the format told from CiA 306 text, and a
// node configured from the concise DCF of its DCF the same as from the DCF.
#include "advee/canopen/concise_dcf.hpp"

#include <gtest/gtest.h>

#include "advee/canopen/node_boot.hpp"
#include "advee/canopen/sim/drive_sim.hpp"
#include "advee/canopen/virtual_bus.hpp"

namespace advee::canopen {
namespace {

using namespace std::chrono_literals;
using Bytes = std::vector<std::uint8_t>;

const std::vector<SdoWrite> kWrites = {
    SdoWrite::of<std::uint16_t>(0x1017, 0, 100),
    SdoWrite::of<std::uint32_t>(0x1801, 1, 0xC0000281),
    SdoWrite{0x2000, 7, {}},  // a zero-length value is legal
};

TEST(ConciseDcfTest, LayoutIsCountThenIndexSubSizeValueLittleEndian) {
  const Bytes want = {3, 0, 0, 0,                                     // entries
                      0x17, 0x10, 0, 2, 0, 0, 0, 100, 0,              // 1017:00 = 100
                      0x01, 0x18, 1, 4, 0, 0, 0, 0x81, 2, 0, 0xC0,    // 1801:01
                      0x00, 0x20, 7, 0, 0, 0, 0};                     // 2000:07, no bytes
  EXPECT_EQ(write_concise_dcf(kWrites), want);
  const ConciseDcfResult r = parse_concise_dcf(want);
  EXPECT_TRUE(r.ok()) << r.error;
  EXPECT_EQ(r.writes, kWrites);
  EXPECT_EQ(write_concise_dcf({}), (Bytes{0, 0, 0, 0}));
  EXPECT_TRUE(parse_concise_dcf(Bytes{0, 0, 0, 0}).ok());
}

TEST(ConciseDcfTest, EveryCutIsRefusedWithItsOffset) {
  const Bytes whole = write_concise_dcf(kWrites);
  for (std::size_t n = 0; n < whole.size(); ++n) {
    const ConciseDcfResult r = parse_concise_dcf(std::span(whole).first(n));
    EXPECT_FALSE(r.ok()) << "cut at " << n;
    EXPECT_TRUE(r.writes.empty());
    EXPECT_EQ(r.error.rfind("byte ", 0), 0u) << r.error;
  }
  EXPECT_EQ(parse_concise_dcf(std::span(whole).first(12)).error,
            "byte 0: entry count 3 needs at least 25 bytes; the file has 12");
  const Bytes one = write_concise_dcf({kWrites[0]});
  EXPECT_EQ(parse_concise_dcf(std::span(one).first(12)).error,
            "byte 11: entry 1 of 1 declares 2 bytes of value; 1 are left");
  EXPECT_EQ(parse_concise_dcf(std::span(whole).first(whole.size() - 5)).error,
            "byte 24: entry 3 of 3 is cut short in its header");
  EXPECT_EQ(parse_concise_dcf(std::span(whole).first(2)).error,
            "byte 0: a concise DCF starts with a 4-byte entry count; the file has 2 bytes");
}

TEST(ConciseDcfTest, ACountOrSizeTheFileCannotHoldAndTrailingBytesAreRefused) {
  Bytes huge = {0xFF, 0xFF, 0xFF, 0x00, 0x17, 0x10, 0, 2, 0, 0, 0};
  EXPECT_EQ(parse_concise_dcf(huge).error, "byte 0: entry count 16777215 needs at least 117440509 bytes; the file has 11");
  Bytes big_size = {1, 0, 0, 0, 0x17, 0x10, 0, 0xFF, 0xFF, 0xFF, 0xFF, 1};
  EXPECT_EQ(parse_concise_dcf(big_size).error, "byte 11: entry 1 of 1 declares 4294967295 bytes of value; 1 are left");
  Bytes trailing = write_concise_dcf(kWrites);
  trailing.push_back(0);
  EXPECT_EQ(parse_concise_dcf(trailing).error, "byte 31: 1 bytes after the last of 3 entries");
  // Every single byte changed: never a crash, either an error or a parse of
  // exactly the same length.
  const Bytes whole = write_concise_dcf(kWrites);
  for (std::size_t i = 0; i < whole.size(); ++i)
    for (const std::uint8_t v : {std::uint8_t{0}, std::uint8_t{0x7F}, std::uint8_t{0xFF}}) {
      Bytes b = whole;
      b[i] = v;
      const ConciseDcfResult r = parse_concise_dcf(b);
      if (r.ok()) {
        EXPECT_EQ(write_concise_dcf(r.writes), b) << "byte " << i;
      }
    }
}

TEST(ConciseDcfTest, TextIsNotTakenForAConciseDcf) {
  const std::string eds(sim::shipped_eds(sim::DriveProfile::kEpos));
  const auto bytes = [](std::string_view s) { return std::span(reinterpret_cast<const std::uint8_t*>(s.data()), s.size()); };
  EXPECT_FALSE(looks_like_concise_dcf(bytes(eds)));
  EXPECT_FALSE(looks_like_concise_dcf(bytes("[1")));
  EXPECT_TRUE(looks_like_concise_dcf(write_concise_dcf(kWrites)));
  EXPECT_TRUE(looks_like_concise_dcf(write_concise_dcf({})));
}

// The concise DCF of a DCF's configuration, downloaded by NodeBoot (no
// identity to check), leaves the simulated EPOS as the DCF itself does.
TEST(ConciseDcfTest, ANodeBootsFromTheConciseDcfOfItsDcf) {
  std::string t(sim::shipped_eds(sim::DriveProfile::kEpos));
  t.insert(t.find("\n\n", t.find("[1017]\n")) + 1, "ParameterValue=150\n");
  t.insert(t.find("\n\n", t.find("[1A01sub2]\n")) + 1, "ParameterValue=0x60640020\n");
  t.insert(t.find("\n\n", t.find("[1A01sub0]\n")) + 1, "ParameterValue=2\n");
  t += "\n[DeviceComissioning]\nNodeID=1\nNodeName=epos\n";
  DescriptionResult d = parse_device_description(t, "epos.dcf");
  ASSERT_TRUE(d.description) << (d.errors.empty() ? "" : d.errors[0].text());
  const NodeBootConfig from_dcf = boot_config_from_dcf(*d.description, "epos");
  const ConciseDcfResult concise = parse_concise_dcf(write_concise_dcf(from_dcf.configuration));
  ASSERT_TRUE(concise.ok()) << concise.error;
  ASSERT_EQ(concise.writes, from_dcf.configuration);

  ManualClock clock;
  VirtualBus bus;
  std::unique_ptr<Master> master;
  std::unique_ptr<sim::SimulatedDrive> drive;
  const std::size_t mport = bus.attach([&](const CanFrame& f) { master->handle(f); });
  const std::size_t dport = bus.attach([&](const CanFrame& f) { drive->handle(f); });
  master = std::make_unique<Master>(MasterConfig{0x7F, 100ms, 50ms}, bus.sender(mport), clock.fn());
  drive = std::make_unique<sim::SimulatedDrive>(sim::DriveSimConfig{1, sim::DriveProfile::kEpos}, bus.sender(dport),
                                                clock.fn());
  drive->power_on();
  bus.deliver();
  NodeBootConfig cfg;
  cfg.node = 1;
  cfg.name = "epos";
  cfg.configuration = concise.writes;
  NodeBoot boot(*master, cfg);
  std::optional<std::string> error;
  boot.boot([&](std::error_code, const std::string& e) { error = e; });
  for (int i = 0; i < 5000 && !error; ++i) {
    clock.advance(1ms);
    master->poll();
    drive->poll();
    bus.deliver();
  }
  ASSERT_TRUE(error);
  EXPECT_EQ(*error, "");
  EXPECT_EQ(drive->nmt_state(), NmtState::kOperational);
  EXPECT_EQ(drive->od().get<std::uint16_t>(0x1017), 150);
  EXPECT_EQ(drive->od().get<std::uint8_t>(0x1A01, 0), 2);
  EXPECT_EQ(drive->od().get<std::uint32_t>(0x1A01, 2), 0x60640020u);
}

}  // namespace
}  // namespace advee::canopen
