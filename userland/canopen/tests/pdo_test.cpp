// SPDX-License-Identifier: GPL-2.0
// PDO codecs built from mappings, the remap procedure as SDO writes, and
// both run against the simulated drive's object dictionary.
#include <gtest/gtest.h>

#include "advee/canopen/master.hpp"
#include "advee/canopen/pdo_config.hpp"
#include "advee/canopen/sim/drive_sim.hpp"
#include "advee/canopen/virtual_bus.hpp"

namespace advee::canopen {
namespace {

using namespace std::chrono_literals;

PdoMapping epos_rpdo4() {
  PdoMapping m;
  m.kind = PdoKind::kRpdo;
  m.number = 4;
  m.cob_id = 0x501;
  m.entries = {PdoEntry::from_raw(0x60400010), PdoEntry::from_raw(0x60FF0020)};
  return m;
}

TEST(PdoCodecTest, PacksObjectsLsbFirstInMappingOrder) {
  auto c = PdoCodec::build(epos_rpdo4());
  ASSERT_TRUE(c);
  EXPECT_EQ(c->can_id(), 0x501u);
  EXPECT_EQ(c->length(), 6);
  CanFrame f = c->blank();
  EXPECT_TRUE(c->set(f, 0x6040, 0, 0x000F));
  EXPECT_TRUE(c->set(f, 0x60FF, 0, static_cast<std::uint32_t>(-1500)));
  EXPECT_EQ(to_string(f), "501#0F0024FAFFFF");
  EXPECT_EQ(c->get_signed(f, 0x60FF, 0), -1500);
  EXPECT_EQ(c->get_unsigned(f, 0x6040, 0), 0x000Fu);
  EXPECT_FALSE(c->set(f, 0x607A, 0, 1)) << "not mapped";
  EXPECT_FALSE(c->get_unsigned(f, 0x607A, 0));
}

TEST(PdoCodecTest, BitFieldsAndShortFrames) {
  PdoMapping m;
  m.cob_id = 0x181;
  m.entries = {{0x2000, 1, 1}, {0x2000, 2, 3}, {0x2000, 3, 12}};
  auto c = PdoCodec::build(m);
  ASSERT_TRUE(c);
  EXPECT_EQ(c->length(), 2);
  CanFrame f = c->blank();
  c->set(f, 0x2000, 1, 1);
  c->set(f, 0x2000, 2, 0b101);
  c->set(f, 0x2000, 3, 0xABC);
  EXPECT_EQ(f.data[0], 0b11001011);
  EXPECT_EQ(c->get_unsigned(f, 0x2000, 3), 0xABCu);
  EXPECT_EQ(c->get_signed(f, 0x2000, 2), -3);
  f.len = 1;
  EXPECT_FALSE(c->get_unsigned(f, 0x2000, 1)) << "a frame shorter than the mapping is not decoded";
}

TEST(PdoCodecTest, RefusesDisabledAndOversizedMappings) {
  std::string why;
  PdoMapping m = epos_rpdo4();
  m.cob_id |= kPdoCobInvalid;
  EXPECT_FALSE(PdoCodec::build(m, &why));
  EXPECT_EQ(why, "PDO is disabled (COB-ID bit 31 set)");
  m = epos_rpdo4();
  m.entries.push_back(PdoEntry::from_raw(0x607A0020));
  EXPECT_FALSE(PdoCodec::build(m, &why));
  EXPECT_EQ(why, "mapping exceeds 64 bits");
}

TEST(PdoRemapTest, WritesFollowTheSafeProcedure) {
  PdoMapping m;
  m.kind = PdoKind::kTpdo;
  m.number = 4;
  m.cob_id = 0x40000481;
  m.transmission_type = 255;
  m.inhibit_100us = 10;
  m.entries = {PdoEntry::from_raw(0x60410010), PdoEntry::from_raw(0x606C0020)};
  const auto w = pdo_remap_writes(m);
  const std::vector<SdoWrite> want = {
      SdoWrite::of<std::uint32_t>(0x1803, 1, 0xC0000481),  // invalidate
      SdoWrite::of<std::uint8_t>(0x1A03, 0, 0),           // disable mapping
      SdoWrite::of<std::uint32_t>(0x1A03, 1, 0x60410010),
      SdoWrite::of<std::uint32_t>(0x1A03, 2, 0x606C0020),
      SdoWrite::of<std::uint8_t>(0x1A03, 0, 2),  // device validates here
      SdoWrite::of<std::uint8_t>(0x1803, 2, 255),
      SdoWrite::of<std::uint16_t>(0x1803, 3, 10),
      SdoWrite::of<std::uint16_t>(0x1803, 5, 0),
      SdoWrite::of<std::uint32_t>(0x1803, 1, 0x40000481),  // valid again
  };
  EXPECT_EQ(w, want);
}

class PdoOnDriveTest : public testing::Test {
 protected:
  ManualClock clock;
  VirtualBus bus;
  std::size_t mport = bus.attach([this](const CanFrame& f) { master.handle(f); });
  std::size_t dport = bus.attach([this](const CanFrame& f) { drive.handle(f); });
  Master master{MasterConfig{}, bus.sender(mport), clock.fn()};
  sim::SimulatedDrive drive{sim::DriveSimConfig{1, sim::DriveProfile::kEpos}, bus.sender(dport), clock.fn()};

  void SetUp() override {
    drive.power_on();
    bus.deliver();  // the boot-up message comes before any request
  }
  void settle() {
    for (int i = 0; i < 50; ++i) {
      bus.deliver();
      clock.advance(1ms);
      master.poll();
      drive.poll();
    }
    bus.deliver();
  }
};

TEST_F(PdoOnDriveTest, ReadBackGivesTheDevicesMappingNotAnAssumedDefault) {
  std::optional<PdoMapping> got;
  read_pdo_mapping(master.sdo(1), PdoKind::kTpdo, 4, [&](std::error_code ec, const PdoMapping& m) {
    EXPECT_FALSE(ec) << ec.message();
    got = m;
  });
  settle();
  ASSERT_TRUE(got);
  EXPECT_FALSE(got->enabled()) << "EPOS TxPDO4 is invalid by default";
  EXPECT_EQ(got->can_id(), 0x481u);
  EXPECT_EQ(got->inhibit_100us, 10);
  EXPECT_EQ(got->entries, (std::vector<PdoEntry>{PdoEntry::from_raw(0x60410010), PdoEntry::from_raw(0x606C0020)}));
}

TEST_F(PdoOnDriveTest, SafeRemapIsAcceptedAndTakesEffect) {
  PdoMapping want;
  want.kind = PdoKind::kTpdo;
  want.number = 3;
  want.cob_id = 0x40000381;
  want.entries = {PdoEntry::from_raw(0x60410010), PdoEntry::from_raw(0x60640020), PdoEntry::from_raw(0x60610008)};
  std::optional<SdoSequenceResult> res;
  run_sdo_writes(master.sdo(1), pdo_remap_writes(want), [&](const SdoSequenceResult& r) { res = r; });
  settle();
  ASSERT_TRUE(res);
  EXPECT_FALSE(res->error) << res->error.message() << " at step " << res->failed_step;

  std::optional<PdoMapping> got;
  read_pdo_mapping(master.sdo(1), PdoKind::kTpdo, 3, [&](std::error_code, const PdoMapping& m) { got = m; });
  settle();
  ASSERT_TRUE(got);
  EXPECT_TRUE(got->enabled());
  EXPECT_EQ(got->entries, want.entries);

  // In operational the drive now sends 7-byte TPDO3 frames the codec decodes.
  auto codec = PdoCodec::build(*got);
  std::optional<std::uint64_t> sw;
  const Registration sub = master.subscribe(0x381, [&](const CanFrame& f) { sw = codec->get_unsigned(f, 0x6041, 0); });
  master.nmt(NmtCommand::kStart, 1);
  settle();
  ASSERT_TRUE(sw);
  EXPECT_EQ(*sw & 0x4F, 0x40u) << "switch on disabled";
}

TEST_F(PdoOnDriveTest, RemapWithoutInvalidatingFirstIsRefusedByTheDevice) {
  std::optional<SdoSequenceResult> res;
  auto writes = pdo_remap_writes(epos_rpdo4());
  writes.erase(writes.begin());  // skip step 2 of the procedure
  run_sdo_writes(master.sdo(1), writes, [&](const SdoSequenceResult& r) { res = r; });
  settle();
  ASSERT_TRUE(res);
  EXPECT_EQ(res->error, make_error_code(SdoAbort::kUnsupportedAccess));
  EXPECT_EQ(res->failed_step, 0u);
}

TEST_F(PdoOnDriveTest, MappingOverSixtyFourBitsIsRefusedAtSub0) {
  PdoMapping m = epos_rpdo4();
  m.entries.push_back(PdoEntry::from_raw(0x607A0020));
  std::optional<SdoSequenceResult> res;
  run_sdo_writes(master.sdo(1), pdo_remap_writes(m), [&](const SdoSequenceResult& r) { res = r; });
  settle();
  ASSERT_TRUE(res);
  EXPECT_EQ(res->error, make_error_code(SdoAbort::kPdoTooLong));
  EXPECT_EQ(res->failed, SdoWrite::of<std::uint8_t>(0x1603, 0, 3));
}

TEST_F(PdoOnDriveTest, SegmentedUploadOfTheDeviceName) {
  std::string name;
  master.sdo(1).upload(0x1008, 0, [&](const SdoResult& r) { name.assign(r.data.begin(), r.data.end()); });
  settle();
  EXPECT_EQ(name, "EPOS 70/10 (simulated)");
}

TEST_F(PdoOnDriveTest, SegmentedDownloadThenUploadRoundTrips) {
  const std::string text = "steering axis, homed on the left switch";  // 40 bytes: 6 segments
  std::optional<SdoResult> w, r;
  master.sdo(1).download(0x2000, 0, {text.begin(), text.end()}, [&](const SdoResult& x) { w = x; });
  master.sdo(1).upload(0x2000, 0, [&](const SdoResult& x) { r = x; });
  settle();
  ASSERT_TRUE(w && r);
  EXPECT_TRUE(w->ok()) << w->error().message();
  EXPECT_EQ(std::string(r->data.begin(), r->data.end()), text);
}

TEST_F(PdoOnDriveTest, SlowServerTimesOutAndTheAbortResetsIt) {
  drive.sdo().faults().response_delay = 800ms;  // longer than the 500 ms SDO timeout
  std::optional<SdoResult> r;
  master.sdo(1).upload(0x1000, 0, [&](const SdoResult& x) { r = x; });
  for (int i = 0; i < 600 && !r; ++i) settle();
  ASSERT_TRUE(r);
  EXPECT_EQ(r->abort, SdoAbort::kTimeout);
  drive.sdo().faults().response_delay = {};
  settle();  // the late answer arrives and is ignored
  std::optional<SdoResult> r2;
  master.sdo(1).upload(0x1000, 0, [&](const SdoResult& x) { r2 = x; });
  settle();
  ASSERT_TRUE(r2);
  EXPECT_TRUE(r2->ok());
  EXPECT_EQ(load_le<std::uint32_t>(r2->data), 0x00020192u);
}

TEST_F(PdoOnDriveTest, WrongToggleFromServerIsAborted) {
  drive.sdo().faults().wrong_upload_toggle = true;
  std::optional<SdoResult> r;
  master.sdo(1).upload(0x1008, 0, [&](const SdoResult& x) { r = x; });
  settle();
  ASSERT_TRUE(r);
  EXPECT_EQ(r->abort, SdoAbort::kToggleBit);
}

TEST_F(PdoOnDriveTest, InjectedAbortCodeReachesTheCaller) {
  drive.sdo().faults().abort_on[{0x6060, 0}] = SdoAbort::kDataStoreState;
  std::optional<SdoResult> r;
  master.sdo(1).write<std::int8_t>(0x6060, 0, 3, [&](const SdoResult& x) { r = x; });
  settle();
  ASSERT_TRUE(r);
  EXPECT_EQ(r->abort, SdoAbort::kDataStoreState);
  EXPECT_TRUE(r->aborted_by_server);
}

}  // namespace
}  // namespace advee::canopen
