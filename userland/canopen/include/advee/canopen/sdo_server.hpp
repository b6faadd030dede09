// SPDX-License-Identifier: GPL-2.0
// SDO server of a node's object dictionary (the master's own, the simulated
// drive's): expedited, segmented and block with CRC, with the fault injections
// the master's tests need (slow responses, forced abort codes, wrong toggle
// bits, silence, no block transfer).
#pragma once

#include <deque>
#include <map>
#include <optional>
#include <utility>

#include "advee/canopen/clock.hpp"
#include "advee/canopen/frame.hpp"
#include "advee/canopen/object_dictionary.hpp"

namespace advee::canopen {

struct SdoServerFaults {
  Duration response_delay{};  // slow server
  bool silent = false;        // never answers
  bool wrong_upload_toggle = false;  // second upload segment carries the wrong toggle
  std::map<std::pair<std::uint16_t, std::uint8_t>, SdoAbort> abort_on;  // forced aborts
  bool refuse_block = false;  // a server without block transfer: abort 0x05040001
  std::uint8_t block_size = 16;  // segments per block it takes on download
};

class SdoServer {
 public:
  SdoServer(std::uint8_t node, ObjectDictionary& od, FrameSender send, NowFn now);

  bool handle(const CanFrame& f);
  void poll();  // sends delayed responses
  std::optional<TimePoint> deadline() const;
  SdoServerFaults& faults() { return faults_; }
  void reset();  // NMT reset communication: drop any transfer in progress
  std::uint64_t requests() const { return requests_; }

 private:
  void respond(const std::array<std::uint8_t, 8>& b);
  void abort(std::uint16_t index, std::uint8_t sub, SdoAbort code);
  void on_initiate_download(const CanFrame& f);
  std::size_t unsized_expedited_length(std::uint16_t index, std::uint8_t sub, const CanFrame& f) const;
  void on_download_segment(const CanFrame& f);
  void on_initiate_upload(const CanFrame& f);
  void on_upload_segment(const CanFrame& f);
  void on_block_upload(const CanFrame& f);
  void on_block_download(const CanFrame& f);
  void on_block_download_segment(const CanFrame& f);
  void send_upload_block();

  std::uint8_t node_;
  ObjectDictionary& od_;
  FrameSender send_;
  NowFn now_;
  SdoServerFaults faults_;
  enum class Phase {
    kIdle,
    kDownload,
    kUpload,
    kBlockDownload,     // segments of a block arriving
    kBlockDownloadEnd,  // all data in, the end awaited
    kBlockUploadStart,  // initiate answered, the client's start awaited
    kBlockUploadAck,    // a block sent, its acknowledgement awaited
    kBlockUploadEnd,    // end sent, the client's end awaited
  } phase_ = Phase::kIdle;
  std::uint16_t index_ = 0;
  std::uint8_t sub_ = 0;
  bool toggle_ = false;
  std::vector<std::uint8_t> buffer_;
  std::size_t offset_ = 0;
  std::size_t segments_sent_ = 0;
  // Block transfer: CRC agreed, segments per block, the block's start and
  // the last segment received in sequence.
  bool crc_ = false;
  std::uint8_t block_size_ = 0;
  std::size_t block_start_ = 0;
  std::uint8_t seqno_ = 0;
  std::deque<std::pair<TimePoint, CanFrame>> delayed_;
  std::uint64_t requests_ = 0;
};

}  // namespace advee::canopen
