// SPDX-License-Identifier: GPL-2.0
// SDO client driven through the virtual bus by a scripted server and a manual
// clock: every path of canopen-notes.md §3.4.
#include "advee/canopen/sdo_client.hpp"

#include <gtest/gtest.h>

#include "advee/canopen/virtual_bus.hpp"

namespace advee::canopen {
namespace {

using namespace std::chrono_literals;

class SdoClientTest : public testing::Test {
 protected:
  ManualClock clock;
  VirtualBus bus;
  std::vector<CanFrame> at_server;
  std::size_t client_port = bus.attach([this](const CanFrame& f) { client.handle(f); });
  std::size_t server_port = bus.attach([this](const CanFrame& f) { at_server.push_back(f); });
  SdoClient client{5, bus.sender(client_port), clock.fn(), 100ms};
  std::vector<SdoResult> results;

  SdoCallback record() {
    return [this](const SdoResult& r) { results.push_back(r); };
  }
  void reply(std::initializer_list<std::uint8_t> bytes) {
    CanFrame f = make_frame(0x585, bytes);
    f.len = 8;  // SDO frames are always 8 bytes
    bus.sender(server_port)(f);
    bus.deliver();
  }
  CanFrame last_request() {
    bus.deliver();
    EXPECT_FALSE(at_server.empty());
    return at_server.empty() ? CanFrame{} : at_server.back();
  }
  static CanFrame request(std::initializer_list<std::uint8_t> bytes) {
    CanFrame f = make_frame(0x605, bytes);
    f.len = 8;
    return f;
  }
};

TEST_F(SdoClientTest, ExpeditedDownloadSendsSizedInitiateAndCompletesOnConfirm) {
  client.write<std::uint16_t>(0x6040, 0x00, 0x000F, record());
  EXPECT_EQ(last_request(), request({0x2B, 0x40, 0x60, 0x00, 0x0F, 0x00, 0x00, 0x00}));
  reply({0x60, 0x40, 0x60, 0x00});
  ASSERT_EQ(results.size(), 1u);
  EXPECT_TRUE(results[0].ok());
  EXPECT_FALSE(client.busy());
}

TEST_F(SdoClientTest, ExpeditedDownloadCommandByteEncodesUnusedBytes) {
  client.write<std::uint8_t>(0x6060, 0x00, 3, record());
  EXPECT_EQ(last_request().data[0], 0x2F);
  reply({0x60, 0x60, 0x60, 0x00});
  client.write<std::uint32_t>(0x60FF, 0x00, 0x12345678, record());
  EXPECT_EQ(last_request(), request({0x23, 0xFF, 0x60, 0x00, 0x78, 0x56, 0x34, 0x12}));
}

TEST_F(SdoClientTest, ExpeditedUploadReturnsTheIndicatedBytes) {
  std::optional<std::uint16_t> got;
  client.read<std::uint16_t>(0x6041, 0, [&](std::error_code ec, std::uint16_t v) {
    EXPECT_FALSE(ec);
    got = v;
  });
  EXPECT_EQ(last_request(), request({0x40, 0x41, 0x60, 0x00}));
  reply({0x4B, 0x41, 0x60, 0x00, 0x37, 0x02});
  EXPECT_EQ(got, 0x0237);
}

TEST_F(SdoClientTest, ReadOfWrongLengthIsTypeMismatch) {
  std::error_code got;
  client.read<std::uint32_t>(0x6041, 0, [&](std::error_code ec, std::uint32_t) { got = ec; });
  reply({0x4B, 0x41, 0x60, 0x00, 0x37, 0x02});
  EXPECT_EQ(got, make_error_code(SdoAbort::kTypeMismatch));
}

TEST_F(SdoClientTest, SegmentedDownloadAlternatesToggleAndMarksLastSegment) {
  std::vector<std::uint8_t> data{1, 2, 3, 4, 5, 6, 7, 8, 9, 10};
  client.download(0x1008, 0x00, data, record());
  EXPECT_EQ(last_request(), request({0x21, 0x08, 0x10, 0x00, 10, 0, 0, 0}));
  reply({0x60, 0x08, 0x10, 0x00});
  EXPECT_EQ(last_request(), request({0x00, 1, 2, 3, 4, 5, 6, 7}));
  reply({0x20});
  // toggle 1, 4 unused bytes, last segment
  EXPECT_EQ(last_request(), request({0x19, 8, 9, 10}));
  EXPECT_TRUE(results.empty());
  reply({0x30});
  ASSERT_EQ(results.size(), 1u);
  EXPECT_TRUE(results[0].ok());
}

TEST_F(SdoClientTest, SegmentedUploadReassemblesAndChecksIndicatedSize) {
  client.upload(0x1008, 0x00, record());
  reply({0x41, 0x08, 0x10, 0x00, 10, 0, 0, 0});
  EXPECT_EQ(last_request(), request({0x60}));
  reply({0x00, 'E', 'P', 'O', 'S', ' ', '7', '0'});
  EXPECT_EQ(last_request(), request({0x70}));
  reply({0x19, '/', '1', '0'});
  ASSERT_EQ(results.size(), 1u);
  ASSERT_TRUE(results[0].ok());
  EXPECT_EQ(std::string(results[0].data.begin(), results[0].data.end()), "EPOS 70/10");
}

TEST_F(SdoClientTest, UploadShorterThanIndicatedIsAborted) {
  client.upload(0x1008, 0x00, record());
  reply({0x41, 0x08, 0x10, 0x00, 10, 0, 0, 0});
  reply({0x01 | (4 << 1), 'a', 'b', 'c'});
  ASSERT_EQ(results.size(), 1u);
  EXPECT_EQ(results[0].abort, SdoAbort::kTooShort);
  EXPECT_EQ(last_request(), request({0x80, 0x08, 0x10, 0x00, 0x13, 0x00, 0x07, 0x06}));
}

TEST_F(SdoClientTest, UploadToggleErrorSendsAbort05030000) {
  client.upload(0x1008, 0x00, record());
  reply({0x41, 0x08, 0x10, 0x00, 10, 0, 0, 0});
  reply({0x00, 1, 2, 3, 4, 5, 6, 7});
  reply({0x09, 8, 9, 10});  // toggle should be 1
  ASSERT_EQ(results.size(), 1u);
  EXPECT_EQ(results[0].abort, SdoAbort::kToggleBit);
  EXPECT_FALSE(results[0].aborted_by_server);
  EXPECT_EQ(last_request(), request({0x80, 0x08, 0x10, 0x00, 0x00, 0x00, 0x03, 0x05}));
}

TEST_F(SdoClientTest, DownloadToggleErrorSendsAbort05030000) {
  client.download(0x2000, 0x01, std::vector<std::uint8_t>(12, 0xAA), record());
  reply({0x60, 0x00, 0x20, 0x01});
  reply({0x30});  // server echoed toggle 1 for the first segment
  ASSERT_EQ(results.size(), 1u);
  EXPECT_EQ(results[0].abort, SdoAbort::kToggleBit);
  EXPECT_EQ(last_request(), request({0x80, 0x00, 0x20, 0x01, 0x00, 0x00, 0x03, 0x05}));
}

TEST_F(SdoClientTest, ServerAbortIsReportedWithItsCode) {
  client.upload(0x2222, 0x03, record());
  reply({0x80, 0x22, 0x22, 0x03, 0x00, 0x00, 0x02, 0x06});
  ASSERT_EQ(results.size(), 1u);
  EXPECT_EQ(results[0].abort, SdoAbort::kNoObject);
  EXPECT_TRUE(results[0].aborted_by_server);
  EXPECT_EQ(results[0].error().message(), "object does not exist in the object dictionary (0x06020000)");
  EXPECT_EQ(at_server.size(), 1u) << "the client must not answer a server abort";
}

TEST_F(SdoClientTest, ServerAbortDuringSegmentedDownloadStopsTheTransfer) {
  client.download(0x2000, 0x01, std::vector<std::uint8_t>(20, 1), record());
  reply({0x60, 0x00, 0x20, 0x01});
  reply({0x80, 0x00, 0x20, 0x01, 0x20, 0x00, 0x00, 0x08});
  ASSERT_EQ(results.size(), 1u);
  EXPECT_EQ(results[0].abort, SdoAbort::kDataStore);
  EXPECT_EQ(at_server.size(), 2u);
}

TEST_F(SdoClientTest, TimeoutSendsAbort05040000AtTheDeadlineNotBefore) {
  client.upload(0x6041, 0x00, record());
  bus.deliver();
  ASSERT_TRUE(client.deadline().has_value());
  EXPECT_EQ(*client.deadline(), clock.now() + 100ms);
  clock.advance(99ms);
  client.poll();
  bus.deliver();
  EXPECT_TRUE(results.empty());
  EXPECT_EQ(at_server.size(), 1u);
  clock.advance(1ms);
  client.poll();
  ASSERT_EQ(results.size(), 1u);
  EXPECT_EQ(results[0].abort, SdoAbort::kTimeout);
  EXPECT_FALSE(results[0].aborted_by_server);
  EXPECT_EQ(last_request(), request({0x80, 0x41, 0x60, 0x00, 0x00, 0x00, 0x04, 0x05}));
  EXPECT_FALSE(client.deadline().has_value());
}

TEST_F(SdoClientTest, EachSegmentRestartsTheTimeout) {
  client.upload(0x1008, 0x00, record());
  clock.advance(80ms);
  reply({0x41, 0x08, 0x10, 0x00, 10, 0, 0, 0});
  clock.advance(80ms);
  client.poll();
  EXPECT_TRUE(results.empty()) << "160 ms in total, but only 80 ms since the last request";
}

TEST_F(SdoClientTest, OneTransferAtATimeTheRestIsQueuedInOrder) {
  client.upload(0x1000, 0, record());
  client.upload(0x1001, 0, record());
  client.write<std::uint8_t>(0x6060, 0, 1, record());
  bus.deliver();
  EXPECT_EQ(at_server.size(), 1u);
  EXPECT_EQ(client.queued(), 2u);
  reply({0x43, 0x00, 0x10, 0x00, 0x92, 0x01, 0x02, 0x00});
  EXPECT_EQ(last_request(), request({0x40, 0x01, 0x10, 0x00}));
  reply({0x4F, 0x01, 0x10, 0x00, 0x00});
  EXPECT_EQ(last_request(), request({0x2F, 0x60, 0x60, 0x00, 0x01}));
  reply({0x60, 0x60, 0x60, 0x00});
  ASSERT_EQ(results.size(), 3u);
  EXPECT_EQ(results[0].data, (std::vector<std::uint8_t>{0x92, 0x01, 0x02, 0x00}));
  EXPECT_EQ(results[1].data, (std::vector<std::uint8_t>{0x00}));
  EXPECT_TRUE(results[2].ok());
}

TEST_F(SdoClientTest, TimeoutOfOneRequestLetsTheNextOneStart) {
  client.upload(0x1000, 0, record());
  client.upload(0x1001, 0, record());
  clock.advance(100ms);
  client.poll();
  bus.deliver();
  ASSERT_EQ(at_server.size(), 3u);  // request, abort, next request
  EXPECT_EQ(at_server[2], request({0x40, 0x01, 0x10, 0x00}));
}

TEST_F(SdoClientTest, ResponseForAnotherObjectIsIgnored) {
  client.upload(0x1001, 0, record());
  reply({0x4F, 0x00, 0x10, 0x00, 0x11});  // late answer to an aborted 0x1000 read
  EXPECT_TRUE(results.empty());
  reply({0x4F, 0x01, 0x10, 0x00, 0x22});
  ASSERT_EQ(results.size(), 1u);
  EXPECT_EQ(results[0].data, std::vector<std::uint8_t>{0x22});
}

TEST_F(SdoClientTest, UnknownServerCommandIsAbortedWith05040001) {
  client.upload(0x1000, 0, record());
  reply({0xE0, 0x00, 0x10, 0x00});
  ASSERT_EQ(results.size(), 1u);
  EXPECT_EQ(results[0].abort, SdoAbort::kUnknownCommand);
  EXPECT_EQ(last_request(), request({0x80, 0x00, 0x10, 0x00, 0x01, 0x00, 0x04, 0x05}));
}

TEST_F(SdoClientTest, FramesOfOtherNodesAreNotConsumed) {
  EXPECT_FALSE(client.handle(make_frame(0x586, {0x60})));
  EXPECT_TRUE(client.handle(make_frame(0x585, {0x60})));
}

TEST_F(SdoClientTest, CancelAllCompletesEverythingAndAbortsTheActiveTransfer) {
  client.upload(0x1000, 0, record());
  client.upload(0x1001, 0, record());
  client.cancel_all(SdoAbort::kGeneral);
  ASSERT_EQ(results.size(), 2u);
  EXPECT_EQ(results[0].abort, SdoAbort::kGeneral);
  EXPECT_EQ(results[1].abort, SdoAbort::kGeneral);
  EXPECT_EQ(last_request().data[0], 0x80);
  EXPECT_FALSE(client.busy());
}

TEST_F(SdoClientTest, CallbackMayQueueTheNextRequest) {
  client.upload(0x1000, 0, [this](const SdoResult&) { client.upload(0x1018, 1, record()); });
  reply({0x43, 0x00, 0x10, 0x00, 1, 2, 3, 4});
  EXPECT_EQ(last_request(), request({0x40, 0x18, 0x10, 0x01}));
}

TEST_F(SdoClientTest, LateAnswerOfAnotherKindDoesNotAbortTheNextTransfer) {
  client.write<std::int8_t>(0x6060, 0, 3, record());
  reply({0x4F, 0x00, 0x10, 0x00, 0x11});  // late upload answer for 0x1000 (a transfer given up)
  EXPECT_TRUE(results.empty()) << "the download must not end on an answer for another object";
  EXPECT_EQ(at_server.size(), 1u) << "no abort frame: " << to_string(at_server.back());
  reply({0x60, 0x60, 0x60, 0x00});
  ASSERT_EQ(results.size(), 1u);
  EXPECT_TRUE(results[0].ok()) << results[0].error().message();
  // And the other way round: a late download confirmation during an upload.
  client.upload(0x1001, 0, record());
  reply({0x60, 0x40, 0x60, 0x00});
  EXPECT_EQ(results.size(), 1u);
  reply({0x4F, 0x01, 0x10, 0x00, 0x22});
  ASSERT_EQ(results.size(), 2u);
  EXPECT_TRUE(results[1].ok()) << results[1].error().message();
}

TEST_F(SdoClientTest, ServerAbortWithAnotherIndexEndsTheTransferAtOnce) {
  client.upload(0x1001, 0, record());
  // Some servers fill the abort's multiplexer with zeros.
  reply({0x80, 0x00, 0x00, 0x00, 0x00, 0x00, 0x02, 0x06});
  ASSERT_EQ(results.size(), 1u) << "the abort must end the transfer, not the timeout";
  EXPECT_EQ(results[0].abort, SdoAbort::kNoObject);
  EXPECT_TRUE(results[0].aborted_by_server);
}

TEST_F(SdoClientTest, LateServerAbortOfATransferGivenUpIsIgnored) {
  client.upload(0x1000, 0, record());
  client.upload(0x1001, 0, record());
  clock.advance(100ms);
  client.poll();  // 0x1000 times out, 0x1001 starts
  ASSERT_EQ(results.size(), 1u);
  reply({0x80, 0x00, 0x10, 0x00, 0x00, 0x00, 0x04, 0x05});  // the server's late abort of 0x1000
  EXPECT_EQ(results.size(), 1u);
  reply({0x4F, 0x01, 0x10, 0x00, 0x22});
  ASSERT_EQ(results.size(), 2u);
  EXPECT_TRUE(results[1].ok());
}

TEST_F(SdoClientTest, ZeroLengthDownloadIsExpeditedWithoutSize) {
  client.download(0x2000, 1, {}, record());
  EXPECT_EQ(last_request(), request({0x22, 0x00, 0x20, 0x01})) << "not a segmented initiate with size 0";
  reply({0x60, 0x00, 0x20, 0x01});
  ASSERT_EQ(results.size(), 1u);
  EXPECT_TRUE(results[0].ok());
  EXPECT_EQ(at_server.size(), 1u) << "no segment follows";
}

TEST(SdoAbortTest, UnknownVendorCodeStillHasAMessage) {
  EXPECT_EQ(describe(static_cast<SdoAbort>(0x12345678)), "unknown abort code");
  EXPECT_EQ(describe(SdoAbort::kTimeout), "SDO protocol timed out");
}

}  // namespace
}  // namespace advee::canopen
