// SPDX-License-Identifier: GPL-2.0
// SDO block transfer (CiA 301 §7.2.4.3.9-16) between the client and the
// simulated drive's server on the virtual bus, manual clock: both ways, at
// the sizes where segments and blocks end, with the block sizes of both
// sides, segments lost on the way, CRC errors either way and a server that
// refuses block transfer.
#include <gtest/gtest.h>

#include <numeric>
#include <string_view>

#include "advee/canopen/sdo_client.hpp"
#include "advee/canopen/sdo_crc.hpp"
#include "advee/canopen/sdo_server.hpp"
#include "advee/canopen/virtual_bus.hpp"

namespace advee::canopen {
namespace {

using namespace std::chrono_literals;

constexpr std::uint16_t kDomain = 0x2000;  // a variable-size read-write object

std::vector<std::uint8_t> pattern(std::size_t n) {
  std::vector<std::uint8_t> v(n);
  std::iota(v.begin(), v.end(), std::uint8_t{1});
  return v;
}

class SdoBlockTest : public testing::Test {
 protected:
  // Returns false to lose the frame on its way; may change it.
  using Tamper = std::function<bool(CanFrame&)>;

  ManualClock clock;
  VirtualBus bus;
  ObjectDictionary od;
  Tamper to_server = [](CanFrame&) { return true; };
  Tamper to_client = [](CanFrame&) { return true; };
  std::size_t client_port = bus.attach([this](const CanFrame& f) { client.handle(f); });
  std::size_t server_port = bus.attach([this](const CanFrame& f) { server.handle(f); });
  SdoClient client{5, through(client_port, to_server), clock.fn(), 100ms};
  SdoServer server{5, od, through(server_port, to_client), clock.fn()};
  std::vector<SdoResult> results;

  void SetUp() override { od.add_string(kDomain, 0, "", Access::kReadWrite); }

  FrameSender through(std::size_t port, Tamper& tamper) {
    return [this, port, &tamper](const CanFrame& f) {
      CanFrame copy = f;
      if (tamper(copy)) bus.sender(port)(copy);
    };
  }
  SdoCallback record() {
    return [this](const SdoResult& r) { results.push_back(r); };
  }
  std::vector<std::uint8_t> stored() const { return od.find(kDomain, 0)->value; }
  std::size_t count(std::uint32_t id, std::uint8_t mask, std::uint8_t value) const {
    std::size_t n = 0;
    for (const CanFrame& f : bus.log()) n += f.id == id && (f.data[0] & mask) == value;
    return n;
  }
  // Block upload of `data` stored in the server, `block_size` segments per block.
  void expect_upload(const std::vector<std::uint8_t>& data, std::uint8_t block_size) {
    ASSERT_EQ(od.write(kDomain, 0, data), SdoAbort::kNone);
    client.set_block_size(block_size);
    client.block_upload(kDomain, 0, record());
    bus.deliver();
    ASSERT_EQ(results.size(), 1u);
    EXPECT_TRUE(results[0].ok()) << results[0].error().message();
    EXPECT_EQ(results[0].data, data);
  }
  // The n-th frame (from 1) that passes `pick` is lost, once.
  static Tamper lose(std::size_t n, std::function<bool(const CanFrame&)> pick) {
    return [n, pick, seen = std::size_t{0}](CanFrame& f) mutable { return !(pick(f) && ++seen == n); };
  }
};

TEST(SdoBlockCrc, IsCrc16CcittWithInitialValueZero) {
  constexpr std::string_view check = "123456789";
  const std::vector<std::uint8_t> bytes(check.begin(), check.end());
  EXPECT_EQ(sdo_block_crc(bytes), 0x31C3);
  EXPECT_EQ(sdo_block_crc({}), 0x0000);
}

class SdoBlockSizes : public SdoBlockTest, public testing::WithParamInterface<std::size_t> {};

TEST_P(SdoBlockSizes, DownloadArrivesWhole) {
  const auto data = pattern(GetParam());
  server.faults().block_size = 4;
  client.block_download(kDomain, 0, data, record());
  bus.deliver();
  ASSERT_EQ(results.size(), 1u);
  EXPECT_TRUE(results[0].ok()) << results[0].error().message();
  EXPECT_EQ(stored(), data);
  if (!data.empty()) {
    EXPECT_EQ(count(0x605, 0xE1, 0xC0), 1u) << "one block initiate";
    // Acknowledgements: one per block of 4 segments of 7 bytes.
    EXPECT_EQ(count(0x585, 0xFF, 0xA2), (data.size() + 27) / 28);
  }
}

TEST_P(SdoBlockSizes, UploadArrivesWhole) {
  const auto data = pattern(GetParam());
  expect_upload(data, 5);
  EXPECT_EQ(count(0x605, 0xFF, 0xA2), std::max<std::size_t>(1, (data.size() + 34) / 35));
}

// Segment and block boundaries: none, one byte, one segment, one more, one
// block of 4 (download) or 5 (upload) segments, and many blocks.
INSTANTIATE_TEST_SUITE_P(Boundaries, SdoBlockSizes, testing::Values(0, 1, 7, 8, 28, 29, 35, 36, 1000));

// 127 segments per block: sequence numbers such as 0x40 and 0x60 look like
// the command bytes of other SDO responses.
TEST_F(SdoBlockTest, UploadTakesSequenceNumbersThatLookLikeCommands) {
  expect_upload(pattern(127 * 7 + 3), 127);
}

TEST_F(SdoBlockTest, DownloadSegmentLostIsSentAgainFromTheLastAcknowledged) {
  const auto data = pattern(100);
  server.faults().block_size = 8;
  to_server = lose(1, [](const CanFrame& f) { return (f.data[0] & 0x7F) == 3; });
  client.block_download(kDomain, 0, data, record());
  bus.deliver();
  ASSERT_EQ(results.size(), 1u);
  EXPECT_TRUE(results[0].ok()) << results[0].error().message();
  EXPECT_EQ(stored(), data);
  // The first block was acknowledged up to segment 2 only.
  const auto acks = count(0x585, 0xFF, 0xA2);
  EXPECT_EQ(acks, 3u);  // 15 segments: 8 (2 taken), 8 (all taken), 5
}

TEST_F(SdoBlockTest, UploadSegmentLostIsSentAgainFromTheLastAcknowledged) {
  const auto data = pattern(100);
  ASSERT_EQ(od.write(kDomain, 0, data), SdoAbort::kNone);
  client.set_block_size(8);
  bool lost = false;
  to_client = [&lost](CanFrame& f) {
    if (lost || f.data[0] != 5) return true;
    lost = true;
    return false;
  };
  client.block_upload(kDomain, 0, record());
  bus.deliver();
  ASSERT_TRUE(lost);
  ASSERT_EQ(results.size(), 1u);
  EXPECT_TRUE(results[0].ok()) << results[0].error().message();
  EXPECT_EQ(results[0].data, data);
  bool acked_four = false;
  for (const CanFrame& f : bus.log()) acked_four |= f.id == 0x605 && f.data[0] == 0xA2 && f.data[1] == 4;
  EXPECT_TRUE(acked_four) << "the block with segment 5 lost is acknowledged up to 4";
}

TEST_F(SdoBlockTest, DownloadCrcErrorIsRefusedByTheServer) {
  ASSERT_EQ(od.write(kDomain, 0, pattern(3)), SdoAbort::kNone);
  // Segment 2's data changed on the way: only the CRC can tell.
  to_server = [](CanFrame& f) {
    if (f.data[0] == 2) f.data[4] ^= 0x01;
    return true;
  };
  client.block_download(kDomain, 0, pattern(50), record());
  bus.deliver();
  ASSERT_EQ(results.size(), 1u);
  EXPECT_EQ(results[0].abort, SdoAbort::kCrcError);
  EXPECT_TRUE(results[0].aborted_by_server);
  EXPECT_EQ(stored(), pattern(3)) << "the object keeps its value";
}

TEST_F(SdoBlockTest, UploadCrcErrorAbortsTheTransfer) {
  ASSERT_EQ(od.write(kDomain, 0, pattern(50)), SdoAbort::kNone);
  to_client = [](CanFrame& f) {
    if (f.data[0] == 2) f.data[4] ^= 0x01;
    return true;
  };
  client.block_upload(kDomain, 0, record());
  bus.deliver();
  ASSERT_EQ(results.size(), 1u);
  EXPECT_EQ(results[0].abort, SdoAbort::kCrcError);
  EXPECT_FALSE(results[0].aborted_by_server);
  const CanFrame& last = bus.log().back();
  EXPECT_EQ(last.id, 0x605u);
  EXPECT_EQ(last.data[0], 0x80) << "the client aborts on the bus";
  EXPECT_EQ(load_le<std::uint32_t>(std::span(last.data).subspan(4)), 0x05040004u);
  // The server took the abort: the next transfer works.
  to_client = [](CanFrame&) { return true; };
  client.block_upload(kDomain, 0, record());
  bus.deliver();
  ASSERT_EQ(results.size(), 2u);
  EXPECT_TRUE(results[1].ok());
}

TEST_F(SdoBlockTest, RefusedBlockDownloadGoesSegmented) {
  server.faults().refuse_block = true;
  const auto data = pattern(20);
  client.block_download(kDomain, 0, data, record());
  bus.deliver();
  ASSERT_EQ(results.size(), 1u);
  EXPECT_TRUE(results[0].ok()) << results[0].error().message();
  EXPECT_EQ(stored(), data);
  EXPECT_EQ(count(0x605, 0xFF, 0x21), 1u) << "a segmented initiate after the refusal";
  EXPECT_EQ(count(0x585, 0xFF, 0x80), 1u);
}

TEST_F(SdoBlockTest, RefusedBlockUploadGoesSegmentedOrExpedited) {
  server.faults().refuse_block = true;
  for (std::size_t n : {3, 20}) {
    ASSERT_EQ(od.write(kDomain, 0, pattern(n)), SdoAbort::kNone);
    client.block_upload(kDomain, 0, record());
    bus.deliver();
    ASSERT_FALSE(results.empty());
    EXPECT_TRUE(results.back().ok()) << results.back().error().message();
    EXPECT_EQ(results.back().data, pattern(n));
  }
  EXPECT_EQ(count(0x605, 0xFF, 0x40), 2u);
}

TEST_F(SdoBlockTest, OtherAbortsAtInitiateEndTheTransfer) {
  client.block_upload(0x2001, 0, record());
  client.block_download(0x2001, 0, pattern(10), record());
  bus.deliver();
  ASSERT_EQ(results.size(), 2u);
  EXPECT_EQ(results[0].abort, SdoAbort::kNoObject);
  EXPECT_EQ(results[1].abort, SdoAbort::kNoObject);
  EXPECT_EQ(count(0x605, 0xE0, 0x40), 0u) << "no segmented attempt";
}

TEST_F(SdoBlockTest, ServerSilentInTheMiddleOfABlockTimesOut) {
  ASSERT_EQ(od.write(kDomain, 0, pattern(100)), SdoAbort::kNone);
  client.set_block_size(8);
  to_client = [](CanFrame& f) { return f.data[0] != 8; };  // every block's last segment lost
  client.block_upload(kDomain, 0, record());
  bus.deliver();
  EXPECT_TRUE(results.empty());
  clock.advance(99ms);
  client.poll();
  EXPECT_TRUE(results.empty());
  clock.advance(1ms);
  client.poll();
  bus.deliver();
  ASSERT_EQ(results.size(), 1u);
  EXPECT_EQ(results[0].abort, SdoAbort::kTimeout);
}

}  // namespace
}  // namespace advee::canopen
