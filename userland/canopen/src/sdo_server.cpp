// SPDX-License-Identifier: GPL-2.0
#include "advee/canopen/sdo_server.hpp"

#include <algorithm>

#include "advee/canopen/sdo_crc.hpp"

namespace advee::canopen {

SdoServer::SdoServer(std::uint8_t node, ObjectDictionary& od, FrameSender send, NowFn now)
    : node_(node), od_(od), send_(std::move(send)), now_(std::move(now)) {}

void SdoServer::reset() {
  phase_ = Phase::kIdle;
  buffer_.clear();
  delayed_.clear();
}

void SdoServer::respond(const std::array<std::uint8_t, 8>& b) {
  CanFrame f;
  f.id = cob::kSdoTx + node_;
  f.len = 8;
  f.data = b;
  if (faults_.response_delay.count() > 0)
    delayed_.emplace_back(now_() + faults_.response_delay, f);
  else
    send_(f);
}

void SdoServer::abort(std::uint16_t index, std::uint8_t sub, SdoAbort code) {
  std::array<std::uint8_t, 8> b{0x80, static_cast<std::uint8_t>(index), static_cast<std::uint8_t>(index >> 8), sub};
  store_le<std::uint32_t>(std::span(b).subspan(4), static_cast<std::uint32_t>(code));
  phase_ = Phase::kIdle;
  respond(b);
}

bool SdoServer::handle(const CanFrame& f) {
  if (f.id != cob::kSdoRx + node_ || f.rtr) return false;
  if (f.len != 8) return true;
  ++requests_;
  if (faults_.silent) return true;
  // Download segments of a block carry a sequence number in byte 0.
  if (phase_ == Phase::kBlockDownload && f.data[0] != 0x80) {
    on_block_download_segment(f);
    return true;
  }
  const std::uint8_t cs = f.data[0] & 0xE0;
  switch (cs) {
    case 0x20: on_initiate_download(f); break;
    case 0x00: on_download_segment(f); break;
    case 0x40: on_initiate_upload(f); break;
    case 0x60: on_upload_segment(f); break;
    case 0xA0: on_block_upload(f); break;
    case 0xC0: on_block_download(f); break;
    case 0x80: phase_ = Phase::kIdle; break;  // client abort: forget the transfer
    default: abort(load_le<std::uint16_t>(f.payload().subspan(1, 2)), f.data[3], SdoAbort::kUnknownCommand);
  }
  return true;
}

void SdoServer::on_initiate_download(const CanFrame& f) {
  index_ = load_le<std::uint16_t>(f.payload().subspan(1, 2));
  sub_ = f.data[3];
  if (auto it = faults_.abort_on.find({index_, sub_}); it != faults_.abort_on.end())
    return abort(index_, sub_, it->second);
  const std::uint8_t b0 = f.data[0];
  std::array<std::uint8_t, 8> ok{0x60, f.data[1], f.data[2], f.data[3]};
  if (b0 & 0x02) {  // expedited
    const std::size_t n = (b0 & 0x01) ? 4 - ((b0 >> 2) & 3) : unsized_expedited_length(index_, sub_, f);
    const SdoAbort a = od_.write(index_, sub_, f.payload().subspan(4, n));
    if (a != SdoAbort::kNone) return abort(index_, sub_, a);
    phase_ = Phase::kIdle;
    return respond(ok);
  }
  if (!od_.find(index_, sub_)) return abort(index_, sub_, od_.index_exists(index_) ? SdoAbort::kNoSubindex : SdoAbort::kNoObject);
  buffer_.clear();
  toggle_ = false;
  phase_ = Phase::kDownload;
  respond(ok);
}

// Expedited without size indication: a fixed-size object takes its size, a
// string the bytes up to the first NUL (an empty string is how a zero-length
// download arrives, as CANopenNode reads it).
std::size_t SdoServer::unsized_expedited_length(std::uint16_t index, std::uint8_t sub, const CanFrame& f) const {
  const OdEntry* e = od_.find(index, sub);
  if (e && !e->variable_size && e->value.size() <= 4) return e->value.size();
  std::size_t n = 0;
  while (n < 4 && f.data[4 + n] != 0) ++n;
  return n;
}

void SdoServer::on_download_segment(const CanFrame& f) {
  if (phase_ != Phase::kDownload) return abort(index_, sub_, SdoAbort::kUnknownCommand);
  const std::uint8_t b0 = f.data[0];
  if (((b0 & 0x10) != 0) != toggle_) return abort(index_, sub_, SdoAbort::kToggleBit);
  const std::size_t n = 7 - ((b0 >> 1) & 7);
  buffer_.insert(buffer_.end(), f.data.begin() + 1, f.data.begin() + 1 + static_cast<std::ptrdiff_t>(n));
  std::array<std::uint8_t, 8> ok{static_cast<std::uint8_t>(0x20 | (toggle_ ? 0x10 : 0))};
  toggle_ = !toggle_;
  if (b0 & 1) {
    const SdoAbort a = od_.write(index_, sub_, buffer_);
    if (a != SdoAbort::kNone) return abort(index_, sub_, a);
    phase_ = Phase::kIdle;
  }
  respond(ok);
}

void SdoServer::on_initiate_upload(const CanFrame& f) {
  index_ = load_le<std::uint16_t>(f.payload().subspan(1, 2));
  sub_ = f.data[3];
  if (auto it = faults_.abort_on.find({index_, sub_}); it != faults_.abort_on.end())
    return abort(index_, sub_, it->second);
  std::vector<std::uint8_t> value;
  const SdoAbort a = od_.read(index_, sub_, value);
  if (a != SdoAbort::kNone) return abort(index_, sub_, a);
  std::array<std::uint8_t, 8> b{0, f.data[1], f.data[2], f.data[3]};
  if (!value.empty() && value.size() <= 4) {
    b[0] = static_cast<std::uint8_t>(0x43 | ((4 - value.size()) << 2));
    std::copy(value.begin(), value.end(), b.begin() + 4);
    phase_ = Phase::kIdle;
    return respond(b);
  }
  b[0] = 0x41;
  store_le<std::uint32_t>(std::span(b).subspan(4), static_cast<std::uint32_t>(value.size()));
  buffer_ = std::move(value);
  offset_ = 0;
  segments_sent_ = 0;
  toggle_ = false;
  phase_ = Phase::kUpload;
  respond(b);
}

void SdoServer::on_upload_segment(const CanFrame& f) {
  if (phase_ != Phase::kUpload) return abort(index_, sub_, SdoAbort::kUnknownCommand);
  if (((f.data[0] & 0x10) != 0) != toggle_) return abort(index_, sub_, SdoAbort::kToggleBit);
  const std::size_t n = std::min<std::size_t>(7, buffer_.size() - offset_);
  const bool last = offset_ + n == buffer_.size();
  bool t = toggle_;
  if (faults_.wrong_upload_toggle && segments_sent_ == 1) t = !t;
  std::array<std::uint8_t, 8> b{static_cast<std::uint8_t>((t ? 0x10 : 0) | ((7 - n) << 1) | (last ? 1 : 0))};
  std::copy_n(buffer_.begin() + static_cast<std::ptrdiff_t>(offset_), n, b.begin() + 1);
  offset_ += n;
  ++segments_sent_;
  toggle_ = !toggle_;
  if (last) phase_ = Phase::kIdle;
  respond(b);
}

// Block download (CiA 301 §7.2.4.3.9-12): initiate, blocks of numbered
// segments acknowledged up to the last one in sequence, end with the CRC.
void SdoServer::on_block_download(const CanFrame& f) {
  const std::uint8_t b0 = f.data[0];
  if ((b0 & 0x01) == 0) {  // initiate
    index_ = load_le<std::uint16_t>(f.payload().subspan(1, 2));
    sub_ = f.data[3];
    if (faults_.refuse_block) return abort(index_, sub_, SdoAbort::kUnknownCommand);
    if (auto it = faults_.abort_on.find({index_, sub_}); it != faults_.abort_on.end())
      return abort(index_, sub_, it->second);
    if (!od_.find(index_, sub_))
      return abort(index_, sub_, od_.index_exists(index_) ? SdoAbort::kNoSubindex : SdoAbort::kNoObject);
    crc_ = (b0 & 0x04) != 0;
    block_size_ = faults_.block_size;
    buffer_.clear();
    seqno_ = 0;
    phase_ = Phase::kBlockDownload;
    return respond({0xA4, f.data[1], f.data[2], f.data[3], block_size_});
  }
  if (phase_ != Phase::kBlockDownloadEnd) return abort(index_, sub_, SdoAbort::kUnknownCommand);
  const std::size_t unused = (b0 >> 2) & 7;
  if (unused > buffer_.size()) return abort(index_, sub_, SdoAbort::kTooShort);
  buffer_.resize(buffer_.size() - unused);
  if (crc_ && load_le<std::uint16_t>(f.payload().subspan(1, 2)) != sdo_block_crc(buffer_))
    return abort(index_, sub_, SdoAbort::kCrcError);
  const SdoAbort a = od_.write(index_, sub_, buffer_);
  if (a != SdoAbort::kNone) return abort(index_, sub_, a);
  phase_ = Phase::kIdle;
  respond({0xA1});
}

void SdoServer::on_block_download_segment(const CanFrame& f) {
  const std::uint8_t seqno = f.data[0] & 0x7F;
  const bool last = (f.data[0] & 0x80) != 0;
  bool complete = false;
  if (seqno == seqno_ + 1 && seqno <= block_size_) {
    buffer_.insert(buffer_.end(), f.data.begin() + 1, f.data.begin() + 8);
    seqno_ = seqno;
    complete = last;
  }
  if (seqno != block_size_ && !last) return;
  const std::uint8_t acked = seqno_;
  seqno_ = 0;
  if (complete) phase_ = Phase::kBlockDownloadEnd;
  respond({0xA2, acked, block_size_});
}

// Block upload (CiA 301 §7.2.4.3.13-16); the protocol switch threshold is
// not honoured: a block upload is a block upload here.
void SdoServer::on_block_upload(const CanFrame& f) {
  const std::uint8_t b0 = f.data[0];
  switch (b0 & 0x03) {
    case 0x00: {  // initiate
      index_ = load_le<std::uint16_t>(f.payload().subspan(1, 2));
      sub_ = f.data[3];
      if (faults_.refuse_block) return abort(index_, sub_, SdoAbort::kUnknownCommand);
      if (auto it = faults_.abort_on.find({index_, sub_}); it != faults_.abort_on.end())
        return abort(index_, sub_, it->second);
      block_size_ = f.data[4];
      if (block_size_ == 0 || block_size_ > 127) return abort(index_, sub_, SdoAbort::kInvalidBlockSize);
      std::vector<std::uint8_t> value;
      const SdoAbort a = od_.read(index_, sub_, value);
      if (a != SdoAbort::kNone) return abort(index_, sub_, a);
      crc_ = (b0 & 0x04) != 0;
      buffer_ = std::move(value);
      offset_ = 0;
      phase_ = Phase::kBlockUploadStart;
      std::array<std::uint8_t, 8> b{0xC6, f.data[1], f.data[2], f.data[3]};
      store_le<std::uint32_t>(std::span(b).subspan(4), static_cast<std::uint32_t>(buffer_.size()));
      return respond(b);
    }
    case 0x03:  // start
      if (phase_ != Phase::kBlockUploadStart) return abort(index_, sub_, SdoAbort::kUnknownCommand);
      return send_upload_block();
    case 0x02: {  // acknowledgement
      if (phase_ != Phase::kBlockUploadAck) return abort(index_, sub_, SdoAbort::kUnknownCommand);
      const std::uint8_t acked = f.data[1];
      if (acked > seqno_) return abort(index_, sub_, SdoAbort::kInvalidSequence);
      block_size_ = f.data[2];
      if (block_size_ == 0 || block_size_ > 127) return abort(index_, sub_, SdoAbort::kInvalidBlockSize);
      offset_ = std::min(buffer_.size(), block_start_ + acked * std::size_t{7});
      if (offset_ < buffer_.size() || (buffer_.empty() && acked == 0)) return send_upload_block();
      const std::size_t in_last = buffer_.empty() ? 0 : buffer_.size() - (buffer_.size() - 1) / 7 * 7;
      std::array<std::uint8_t, 8> b{static_cast<std::uint8_t>(0xC1 | ((7 - in_last) << 2))};
      if (crc_) store_le<std::uint16_t>(std::span(b).subspan(1, 2), sdo_block_crc(buffer_));
      phase_ = Phase::kBlockUploadEnd;
      return respond(b);
    }
    default:  // end
      if (phase_ != Phase::kBlockUploadEnd) return abort(index_, sub_, SdoAbort::kUnknownCommand);
      phase_ = Phase::kIdle;
  }
}

// One block from offset_; no data at all still takes one (empty) segment.
void SdoServer::send_upload_block() {
  block_start_ = offset_;
  seqno_ = 0;
  phase_ = Phase::kBlockUploadAck;
  do {
    const std::size_t n = std::min<std::size_t>(7, buffer_.size() - offset_);
    const bool last = offset_ + n == buffer_.size();
    std::array<std::uint8_t, 8> b{static_cast<std::uint8_t>((last ? 0x80 : 0) | ++seqno_)};
    std::copy_n(buffer_.begin() + static_cast<std::ptrdiff_t>(offset_), n, b.begin() + 1);
    offset_ += n;
    respond(b);
  } while (seqno_ < block_size_ && offset_ < buffer_.size());
}

void SdoServer::poll() {
  const TimePoint now = now_();
  while (!delayed_.empty() && delayed_.front().first <= now) {
    send_(delayed_.front().second);
    delayed_.pop_front();
  }
}

std::optional<TimePoint> SdoServer::deadline() const {
  if (delayed_.empty()) return std::nullopt;
  return delayed_.front().first;
}

}  // namespace advee::canopen
