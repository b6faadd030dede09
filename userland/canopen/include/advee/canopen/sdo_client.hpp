// SPDX-License-Identifier: GPL-2.0
// SDO client for one server node (CiA 301 §7.2.4): expedited, segmented and
// block upload/download (block: CRC when the server supports it, the block
// size of each side, retransmission from the last acknowledged segment, and
// segmented transfer when the server refuses block), one outstanding transfer per node with a FIFO queue behind
// it, a per-step timeout that sends abort 0x05040000 so the server resets,
// and typed abort codes for every failure. Passive: it sends through a
// FrameSender, learns about frames through handle() and about time through
// poll(); the caller asks deadline() when poll() is next needed.
#pragma once

#include <chrono>
#include <cstdint>
#include <deque>
#include <functional>
#include <optional>
#include <system_error>
#include <vector>

#include "advee/byte_order.hpp"
#include "advee/canopen/clock.hpp"
#include "advee/canopen/frame.hpp"
#include "advee/canopen/sdo_abort.hpp"

namespace advee::canopen {

struct SdoResult {
  SdoAbort abort = SdoAbort::kNone;
  bool aborted_by_server = false;  // false with an abort code: this client gave up
  std::vector<std::uint8_t> data;  // uploaded bytes

  bool ok() const { return abort == SdoAbort::kNone; }
  std::error_code error() const { return make_error_code(abort); }
};
using SdoCallback = std::function<void(const SdoResult&)>;

class SdoClient {
 public:
  static constexpr Duration kDefaultTimeout = std::chrono::milliseconds(500);
  // Segments per block this client asks for on upload (CiA 301: 1..127).
  // Not 127: a block arrives as one burst and must fit the CAN controller's
  // and the socket's receive queues.
  static constexpr std::uint8_t kDefaultBlockSize = 32;
  static constexpr std::uint8_t kMaxBlockSize = 127;

  SdoClient(std::uint8_t node, FrameSender send, NowFn now, Duration timeout = kDefaultTimeout);
  SdoClient(const SdoClient&) = delete;
  SdoClient& operator=(const SdoClient&) = delete;

  void upload(std::uint16_t index, std::uint8_t sub, SdoCallback done);
  void download(std::uint16_t index, std::uint8_t sub, std::vector<std::uint8_t> data, SdoCallback done);

  // Block transfer; a server that refuses it (abort 0x05040001 to the
  // initiate) gets the same transfer segmented (expedited up to 4 bytes).
  void block_upload(std::uint16_t index, std::uint8_t sub, SdoCallback done);
  void block_download(std::uint16_t index, std::uint8_t sub, std::vector<std::uint8_t> data, SdoCallback done);

  template <typename T>
  void write(std::uint16_t index, std::uint8_t sub, T value, SdoCallback done) {
    download(index, sub, to_bytes<T>(value), std::move(done));
  }
  // Calls done(error, value); a reply of the wrong length is kTypeMismatch.
  template <typename T>
  void read(std::uint16_t index, std::uint8_t sub, std::function<void(std::error_code, T)> done) {
    upload(index, sub, [done = std::move(done)](const SdoResult& r) {
      if (!r.ok()) return done(r.error(), T{});
      if (r.data.size() != sizeof(T)) return done(make_error_code(SdoAbort::kTypeMismatch), T{});
      done({}, load_le<T>(r.data));
    });
  }

  // True if the frame was this server's response channel (0x580 + node).
  bool handle(const CanFrame& frame);
  // Aborts the active transfer if its step timed out.
  void poll();
  std::optional<TimePoint> deadline() const;

  // Completes the active and all queued transfers with `why` (the active one
  // is aborted on the bus too), e.g. when the node resets.
  void cancel_all(SdoAbort why = SdoAbort::kGeneral);

  void set_timeout(Duration t) { timeout_ = t; }
  // 1..kMaxBlockSize; applies to the block uploads that start afterwards.
  void set_block_size(std::uint8_t segments);
  std::uint8_t block_size() const { return block_size_; }
  Duration timeout() const { return timeout_; }
  std::uint8_t node() const { return node_; }
  bool busy() const { return active_.has_value(); }
  std::size_t queued() const { return queue_.size(); }

 private:
  enum class Phase {
    kIdle,
    kDownloadInitiate,
    kDownloadSegment,
    kUploadInitiate,
    kUploadSegment,
    kBlockDownloadInitiate,
    kBlockDownloadAck,  // a block sent, its acknowledgement awaited
    kBlockDownloadEnd,
    kBlockUploadInitiate,
    kBlockUploadSegments,
    kBlockUploadEnd,
  };
  struct Request {
    bool upload = false;
    bool block = false;
    std::uint16_t index = 0;
    std::uint8_t sub = 0;
    std::vector<std::uint8_t> data;
    SdoCallback done;
  };

  void enqueue(Request r);
  void start_next();
  void start_active();
  void send_request(const std::array<std::uint8_t, 8>& bytes);
  void send_download_segment();
  void send_abort(SdoAbort code);
  void abort_local(SdoAbort code);
  void finish(SdoResult result);
  bool initiate_matches(const CanFrame& f) const;
  void on_download_response(const CanFrame& f);
  void on_upload_response(const CanFrame& f);
  bool initiating() const;
  void start_block(std::array<std::uint8_t, 8>& b);
  void send_block();
  void on_block_download_response(const CanFrame& f);
  void on_block_upload_response(const CanFrame& f);
  void on_block_upload_segment(const CanFrame& f);

  std::uint8_t node_;
  FrameSender send_;
  NowFn now_;
  Duration timeout_;
  std::deque<Request> queue_;
  std::optional<Request> active_;
  Phase phase_ = Phase::kIdle;
  bool toggle_ = false;
  std::size_t offset_ = 0;
  std::optional<std::size_t> upload_size_;
  std::vector<std::uint8_t> received_;
  // Block transfer: segments per block, the server's CRC support, where the
  // current block started, segments sent in it / last in-sequence received.
  std::uint8_t block_size_ = kDefaultBlockSize;
  std::uint8_t peer_block_size_ = 0;
  bool crc_ = false;
  std::size_t block_start_ = 0;
  std::uint8_t seqno_ = 0;
  bool last_segment_ = false;
  TimePoint deadline_{};
  // The object of the last transfer this client gave up on (timeout, local
  // abort, cancel): a late server abort for it is not about the active one.
  std::optional<std::pair<std::uint16_t, std::uint8_t>> given_up_;
};

}  // namespace advee::canopen
