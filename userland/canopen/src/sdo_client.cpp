// SPDX-License-Identifier: GPL-2.0
#include "advee/canopen/sdo_client.hpp"

#include <algorithm>

#include "advee/canopen/sdo_crc.hpp"

namespace advee::canopen {

namespace {
// Command specifiers (byte 0), canopen-notes.md §3.4.
constexpr std::uint8_t kCsMask = 0xE0;
constexpr std::uint8_t kAbort = 0x80;
constexpr std::uint8_t kCcsDownloadSegment = 0x00;
constexpr std::uint8_t kCcsInitiateDownload = 0x20;
constexpr std::uint8_t kCcsInitiateUpload = 0x40;
constexpr std::uint8_t kCcsUploadSegment = 0x60;
constexpr std::uint8_t kScsUploadSegment = 0x00;
constexpr std::uint8_t kScsDownloadSegment = 0x20;
constexpr std::uint8_t kScsInitiateUpload = 0x40;
constexpr std::uint8_t kScsInitiateDownload = 0x60;
// Block transfer (CiA 301 §7.2.4.3.9-16): client 0xA0 upload / 0xC0
// download, server 0xC0 upload / 0xA0 download; the low bits are the
// subcommand, the CRC flag and the size flag.
constexpr std::uint8_t kCcsBlockUpload = 0xA0;
constexpr std::uint8_t kCcsBlockDownload = 0xC0;
constexpr std::uint8_t kScsBlockUpload = 0xC0;
constexpr std::uint8_t kScsBlockDownload = 0xA0;
constexpr std::uint8_t kBlockSubMask = 0xE3;  // command specifier and subcommand
constexpr std::uint8_t kBlockInitiateSub = 0x00;
constexpr std::uint8_t kBlockEndSub = 0x01;
constexpr std::uint8_t kBlockAckSub = 0x02;
constexpr std::uint8_t kBlockStartUpload = 0x03;
constexpr std::uint8_t kBlockCrc = 0x04;
constexpr std::uint8_t kBlockSize = 0x02;
constexpr std::uint8_t kLastSegment = 0x80;
constexpr std::uint8_t kSeqnoMask = 0x7F;
constexpr std::uint8_t kToggle = 0x10;
constexpr std::uint8_t kExpedited = 0x02;
constexpr std::uint8_t kSizeIndicated = 0x01;
constexpr std::size_t kSegmentBytes = 7;

// Initiate responses and aborts carry index and sub-index in bytes 1-3;
// segment responses carry data there.
bool carries_multiplexer(const CanFrame& f) {
  const std::uint8_t cs = f.data[0] & kCsMask;
  if (cs == kScsBlockUpload) return (f.data[0] & 0xE1) == (kScsBlockUpload | kBlockInitiateSub);
  if (cs == kScsBlockDownload) return (f.data[0] & kBlockSubMask) == (kScsBlockDownload | kBlockInitiateSub);
  return cs == kScsInitiateUpload || cs == kScsInitiateDownload || f.data[0] == kAbort;
}
std::pair<std::uint16_t, std::uint8_t> multiplexer(const CanFrame& f) {
  return {load_le<std::uint16_t>(std::span(f.data).subspan(1, 2)), f.data[3]};
}
}  // namespace

SdoClient::SdoClient(std::uint8_t node, FrameSender send, NowFn now, Duration timeout)
    : node_(node), send_(std::move(send)), now_(std::move(now)), timeout_(timeout) {}

void SdoClient::upload(std::uint16_t index, std::uint8_t sub, SdoCallback done) {
  enqueue({true, false, index, sub, {}, std::move(done)});
}

void SdoClient::download(std::uint16_t index, std::uint8_t sub, std::vector<std::uint8_t> data,
                         SdoCallback done) {
  enqueue({false, false, index, sub, std::move(data), std::move(done)});
}

void SdoClient::block_upload(std::uint16_t index, std::uint8_t sub, SdoCallback done) {
  enqueue({true, true, index, sub, {}, std::move(done)});
}

void SdoClient::block_download(std::uint16_t index, std::uint8_t sub, std::vector<std::uint8_t> data,
                               SdoCallback done) {
  // Zero bytes have no segment to carry them: expedited.
  const bool block = !data.empty();
  enqueue({false, block, index, sub, std::move(data), std::move(done)});
}

void SdoClient::set_block_size(std::uint8_t segments) {
  block_size_ = std::clamp<std::uint8_t>(segments, 1, kMaxBlockSize);
}

void SdoClient::enqueue(Request r) {
  queue_.push_back(std::move(r));
  start_next();
}

void SdoClient::start_next() {
  if (active_ || queue_.empty()) return;
  active_ = std::move(queue_.front());
  queue_.pop_front();
  start_active();
}

void SdoClient::send_request(const std::array<std::uint8_t, 8>& bytes) {
  CanFrame f;
  f.id = cob::kSdoRx + node_;
  f.len = 8;
  f.data = bytes;
  deadline_ = now_() + timeout_;
  send_(f);
}

void SdoClient::start_active() {
  const Request& r = *active_;
  std::array<std::uint8_t, 8> b{};
  b[1] = static_cast<std::uint8_t>(r.index);
  b[2] = static_cast<std::uint8_t>(r.index >> 8);
  b[3] = r.sub;
  toggle_ = false;
  offset_ = 0;
  received_.clear();
  upload_size_.reset();
  if (r.block) {
    start_block(b);
  } else if (r.upload) {
    phase_ = Phase::kUploadInitiate;
    b[0] = kCcsInitiateUpload;
  } else if (r.data.empty()) {
    // Zero bytes: expedited without size indication. A segmented initiate
    // with size 0 is legal but refused by some servers (CANopenNode).
    phase_ = Phase::kDownloadInitiate;
    b[0] = kCcsInitiateDownload | kExpedited;
  } else if (r.data.size() <= 4) {
    phase_ = Phase::kDownloadInitiate;
    b[0] = static_cast<std::uint8_t>(kCcsInitiateDownload | ((4 - r.data.size()) << 2) | kExpedited |
                                     kSizeIndicated);
    std::copy(r.data.begin(), r.data.end(), b.begin() + 4);
  } else {
    phase_ = Phase::kDownloadInitiate;
    b[0] = kCcsInitiateDownload | kSizeIndicated;
    store_le<std::uint32_t>(std::span(b).subspan(4), static_cast<std::uint32_t>(r.data.size()));
  }
  send_request(b);
}

void SdoClient::start_block(std::array<std::uint8_t, 8>& b) {
  const Request& r = *active_;
  seqno_ = 0;
  last_segment_ = false;
  block_start_ = 0;
  if (r.upload) {
    phase_ = Phase::kBlockUploadInitiate;
    b[0] = kCcsBlockUpload | kBlockCrc | kBlockInitiateSub;
    b[4] = block_size_;
    b[5] = 0;  // protocol switch threshold: none, block whatever the size
  } else {
    phase_ = Phase::kBlockDownloadInitiate;
    b[0] = kCcsBlockDownload | kBlockCrc | kBlockSize | kBlockInitiateSub;
    store_le<std::uint32_t>(std::span(b).subspan(4), static_cast<std::uint32_t>(r.data.size()));
  }
}

// Sends the segments of one block from offset_, numbered from 1; the last
// segment of the data carries kLastSegment.
void SdoClient::send_block() {
  const auto& d = active_->data;
  block_start_ = offset_;
  seqno_ = 0;
  phase_ = Phase::kBlockDownloadAck;
  while (seqno_ < peer_block_size_ && offset_ < d.size()) {
    const std::size_t n = std::min(kSegmentBytes, d.size() - offset_);
    const bool last = offset_ + n == d.size();
    std::array<std::uint8_t, 8> b{};
    b[0] = static_cast<std::uint8_t>((last ? kLastSegment : 0) | ++seqno_);
    std::copy_n(d.begin() + static_cast<std::ptrdiff_t>(offset_), n, b.begin() + 1);
    offset_ += n;
    send_request(b);
  }
}

void SdoClient::send_download_segment() {
  const auto& d = active_->data;
  const std::size_t n = std::min(kSegmentBytes, d.size() - offset_);
  const bool last = offset_ + n == d.size();
  std::array<std::uint8_t, 8> b{};
  b[0] = static_cast<std::uint8_t>(kCcsDownloadSegment | (toggle_ ? kToggle : 0) | ((kSegmentBytes - n) << 1) |
                                   (last ? 1 : 0));
  std::copy_n(d.begin() + static_cast<std::ptrdiff_t>(offset_), n, b.begin() + 1);
  offset_ += n;
  send_request(b);
}

void SdoClient::send_abort(SdoAbort code) {
  std::array<std::uint8_t, 8> b{};
  b[0] = kAbort;
  b[1] = static_cast<std::uint8_t>(active_->index);
  b[2] = static_cast<std::uint8_t>(active_->index >> 8);
  b[3] = active_->sub;
  store_le<std::uint32_t>(std::span(b).subspan(4), static_cast<std::uint32_t>(code));
  send_request(b);
}

void SdoClient::abort_local(SdoAbort code) {
  given_up_.emplace(active_->index, active_->sub);
  send_abort(code);
  finish({code, false, {}});
}

void SdoClient::finish(SdoResult result) {
  Request done = std::move(*active_);
  active_.reset();
  phase_ = Phase::kIdle;
  // The callback may queue the next request; it starts from enqueue() then,
  // otherwise the queue moves on here.
  if (done.done) done.done(result);
  start_next();
}

bool SdoClient::initiate_matches(const CanFrame& f) const {
  return multiplexer(f) == std::pair(active_->index, active_->sub);
}

bool SdoClient::handle(const CanFrame& f) {
  if (f.id != cob::kSdoTx + node_ || f.rtr) return false;
  if (!active_ || f.len < 4) return true;  // stale or stray response: ignore
  // Upload segments of a block carry a sequence number in byte 0, any value
  // but that of an abort (sequence number 0 is not one).
  if (phase_ == Phase::kBlockUploadSegments && f.data[0] != kAbort) {
    on_block_upload_segment(f);
    return true;
  }
  if (f.data[0] == kAbort) {
    // The server has one transfer with us, so its abort ends the active one
    // even when it names another object (some servers send zeros), unless
    // it names the object of a transfer we gave up on: that one is late.
    if (!initiate_matches(f) && multiplexer(f) == given_up_) return true;
    const auto code = static_cast<SdoAbort>(load_le<std::uint32_t>(std::span(f.data).subspan(4)));
    if (code == SdoAbort::kUnknownCommand &&
        (phase_ == Phase::kBlockUploadInitiate || phase_ == Phase::kBlockDownloadInitiate)) {
      // No block transfer on this server: the same transfer segmented.
      active_->block = false;
      start_active();
      return true;
    }
    finish({code, true, {}});
    return true;
  }
  // A response that names another object is a late answer to an older
  // transfer, whatever its kind: checked before the command specifier.
  if (carries_multiplexer(f) && !initiate_matches(f)) return true;
  if (!initiating() && carries_multiplexer(f)) return true;  // a repeated initiate answer
  if (active_->block && active_->upload)
    on_block_upload_response(f);
  else if (active_->block)
    on_block_download_response(f);
  else if (active_->upload)
    on_upload_response(f);
  else
    on_download_response(f);
  return true;
}

bool SdoClient::initiating() const {
  return phase_ == Phase::kDownloadInitiate || phase_ == Phase::kUploadInitiate ||
         phase_ == Phase::kBlockDownloadInitiate || phase_ == Phase::kBlockUploadInitiate;
}

void SdoClient::on_block_download_response(const CanFrame& f) {
  const std::uint8_t b0 = f.data[0];
  const std::uint8_t sub = b0 & kBlockSubMask;
  const auto& d = active_->data;
  if (phase_ == Phase::kBlockDownloadInitiate) {
    if (sub != (kScsBlockDownload | kBlockInitiateSub)) return abort_local(SdoAbort::kUnknownCommand);
    crc_ = (b0 & kBlockCrc) != 0;
    peer_block_size_ = f.data[4];
    if (peer_block_size_ == 0 || peer_block_size_ > kMaxBlockSize) return abort_local(SdoAbort::kInvalidBlockSize);
    return send_block();
  }
  if (phase_ == Phase::kBlockDownloadAck) {
    if (sub != (kScsBlockDownload | kBlockAckSub)) return abort_local(SdoAbort::kUnknownCommand);
    const std::uint8_t acked = f.data[1];
    if (acked > seqno_) return abort_local(SdoAbort::kInvalidSequence);
    peer_block_size_ = f.data[2];
    if (peer_block_size_ == 0 || peer_block_size_ > kMaxBlockSize) return abort_local(SdoAbort::kInvalidBlockSize);
    // Segments after the last acknowledged one go again in the next block.
    offset_ = std::min(d.size(), block_start_ + acked * kSegmentBytes);
    if (offset_ < d.size()) return send_block();
    const std::size_t in_last = d.size() - (d.size() - 1) / kSegmentBytes * kSegmentBytes;
    std::array<std::uint8_t, 8> b{};
    b[0] = static_cast<std::uint8_t>(kCcsBlockDownload | ((kSegmentBytes - in_last) << 2) | kBlockEndSub);
    if (crc_) store_le<std::uint16_t>(std::span(b).subspan(1, 2), sdo_block_crc(d));
    phase_ = Phase::kBlockDownloadEnd;
    return send_request(b);
  }
  if (phase_ == Phase::kBlockDownloadEnd) {
    if (sub != (kScsBlockDownload | kBlockEndSub)) return abort_local(SdoAbort::kUnknownCommand);
    finish({});
  }
}

void SdoClient::on_block_upload_response(const CanFrame& f) {
  const std::uint8_t b0 = f.data[0];
  if (phase_ == Phase::kBlockUploadInitiate) {
    if ((b0 & kCsMask) == kScsInitiateUpload) {
      // The server switched to a segmented or expedited upload.
      active_->block = false;
      phase_ = Phase::kUploadInitiate;
      return on_upload_response(f);
    }
    if ((b0 & 0xE1) != (kScsBlockUpload | kBlockInitiateSub)) return abort_local(SdoAbort::kUnknownCommand);
    crc_ = (b0 & kBlockCrc) != 0;
    if (b0 & kBlockSize) upload_size_ = load_le<std::uint32_t>(std::span(f.data).subspan(4));
    phase_ = Phase::kBlockUploadSegments;
    seqno_ = 0;
    std::array<std::uint8_t, 8> b{};
    b[0] = kCcsBlockUpload | kBlockStartUpload;
    return send_request(b);
  }
  if (phase_ == Phase::kBlockUploadEnd) {
    if ((b0 & kBlockSubMask) != (kScsBlockUpload | kBlockEndSub)) return abort_local(SdoAbort::kUnknownCommand);
    const std::size_t unused = (b0 >> 2) & 7;
    if (unused > received_.size()) return abort_local(SdoAbort::kTooShort);
    // erase, not resize: GCC 12 sees resize()'s growing path and warns
    // (stringop-overflow) though the vector only shrinks here.
    received_.erase(received_.end() - static_cast<std::ptrdiff_t>(unused), received_.end());
    if (upload_size_ && received_.size() < *upload_size_) return abort_local(SdoAbort::kTooShort);
    if (upload_size_ && received_.size() > *upload_size_) return abort_local(SdoAbort::kTooLong);
    if (crc_ && load_le<std::uint16_t>(std::span(f.data).subspan(1, 2)) != sdo_block_crc(received_))
      return abort_local(SdoAbort::kCrcError);
    std::array<std::uint8_t, 8> b{};
    b[0] = kCcsBlockUpload | kBlockEndSub;
    send_request(b);
    SdoResult r;
    r.data = std::move(received_);
    finish(std::move(r));
  }
}

// A segment in sequence is kept; the block is acknowledged at its last
// number or at the data's last segment, naming the last segment received in
// sequence, so the server sends the rest again from there.
void SdoClient::on_block_upload_segment(const CanFrame& f) {
  const std::uint8_t seqno = f.data[0] & kSeqnoMask;
  const bool last = (f.data[0] & kLastSegment) != 0;
  if (seqno == seqno_ + 1 && seqno <= block_size_) {
    received_.insert(received_.end(), f.data.begin() + 1, f.data.begin() + 1 + kSegmentBytes);
    seqno_ = seqno;
    last_segment_ = last;
    deadline_ = now_() + timeout_;
    if (upload_size_ && received_.size() > *upload_size_ + kSegmentBytes) return abort_local(SdoAbort::kTooLong);
  }
  if (seqno != block_size_ && !last) return;
  std::array<std::uint8_t, 8> b{};
  b[0] = kCcsBlockUpload | kBlockAckSub;
  b[1] = seqno_;
  b[2] = block_size_;
  seqno_ = 0;
  if (last_segment_) phase_ = Phase::kBlockUploadEnd;
  send_request(b);
}

void SdoClient::on_download_response(const CanFrame& f) {
  const std::uint8_t cs = f.data[0] & kCsMask;
  if (phase_ == Phase::kDownloadInitiate) {
    if (cs != kScsInitiateDownload) return abort_local(SdoAbort::kUnknownCommand);
    if (active_->data.size() > 4) {
      phase_ = Phase::kDownloadSegment;
      toggle_ = false;
      return send_download_segment();
    }
    return finish({});
  }
  if (phase_ == Phase::kDownloadSegment) {
    if (cs != kScsDownloadSegment) return abort_local(SdoAbort::kUnknownCommand);
    if (((f.data[0] & kToggle) != 0) != toggle_) return abort_local(SdoAbort::kToggleBit);
    if (offset_ >= active_->data.size()) return finish({});
    toggle_ = !toggle_;
    send_download_segment();
  }
}

void SdoClient::on_upload_response(const CanFrame& f) {
  const std::uint8_t b0 = f.data[0];
  const std::uint8_t cs = b0 & kCsMask;
  if (phase_ == Phase::kUploadInitiate) {
    if (cs != kScsInitiateUpload) return abort_local(SdoAbort::kUnknownCommand);
    if (b0 & kExpedited) {
      const std::size_t n = (b0 & kSizeIndicated) ? 4 - ((b0 >> 2) & 3) : 4;
      SdoResult r;
      r.data.assign(f.data.begin() + 4, f.data.begin() + 4 + static_cast<std::ptrdiff_t>(n));
      return finish(std::move(r));
    }
    if (b0 & kSizeIndicated) upload_size_ = load_le<std::uint32_t>(std::span(f.data).subspan(4));
    phase_ = Phase::kUploadSegment;
    toggle_ = false;
    std::array<std::uint8_t, 8> b{};
    b[0] = kCcsUploadSegment;
    return send_request(b);
  }
  if (phase_ == Phase::kUploadSegment) {
    if (cs != kScsUploadSegment) return abort_local(SdoAbort::kUnknownCommand);
    if (((b0 & kToggle) != 0) != toggle_) return abort_local(SdoAbort::kToggleBit);
    const std::size_t n = kSegmentBytes - ((b0 >> 1) & 7);
    received_.insert(received_.end(), f.data.begin() + 1, f.data.begin() + 1 + static_cast<std::ptrdiff_t>(n));
    if (upload_size_ && received_.size() > *upload_size_) return abort_local(SdoAbort::kTooLong);
    if (b0 & 1) {
      if (upload_size_ && received_.size() != *upload_size_) return abort_local(SdoAbort::kTooShort);
      SdoResult r;
      r.data = std::move(received_);
      return finish(std::move(r));
    }
    toggle_ = !toggle_;
    std::array<std::uint8_t, 8> b{};
    b[0] = static_cast<std::uint8_t>(kCcsUploadSegment | (toggle_ ? kToggle : 0));
    send_request(b);
  }
}

void SdoClient::poll() {
  if (active_ && now_() >= deadline_) abort_local(SdoAbort::kTimeout);
}

std::optional<TimePoint> SdoClient::deadline() const {
  if (!active_) return std::nullopt;
  return deadline_;
}

void SdoClient::cancel_all(SdoAbort why) {
  std::deque<Request> pending;
  pending.swap(queue_);
  if (active_) {
    given_up_.emplace(active_->index, active_->sub);
    send_abort(why);
    Request r = std::move(*active_);
    active_.reset();
    phase_ = Phase::kIdle;
    if (r.done) r.done({why, false, {}});
  }
  for (auto& r : pending)
    if (r.done) r.done({why, false, {}});
}

}  // namespace advee::canopen
