// SPDX-License-Identifier: GPL-2.0
#include "advee/canopen/sdo_client.hpp"

#include <algorithm>

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
constexpr std::uint8_t kToggle = 0x10;
constexpr std::uint8_t kExpedited = 0x02;
constexpr std::uint8_t kSizeIndicated = 0x01;
constexpr std::size_t kSegmentBytes = 7;

// Initiate responses and aborts carry index and sub-index in bytes 1-3;
// segment responses carry data there.
bool carries_multiplexer(const CanFrame& f) {
  const std::uint8_t cs = f.data[0] & kCsMask;
  return cs == kScsInitiateUpload || cs == kScsInitiateDownload || f.data[0] == kAbort;
}
std::pair<std::uint16_t, std::uint8_t> multiplexer(const CanFrame& f) {
  return {load_le<std::uint16_t>(std::span(f.data).subspan(1, 2)), f.data[3]};
}
}  // namespace

SdoClient::SdoClient(std::uint8_t node, FrameSender send, NowFn now, Duration timeout)
    : node_(node), send_(std::move(send)), now_(std::move(now)), timeout_(timeout) {}

void SdoClient::upload(std::uint16_t index, std::uint8_t sub, SdoCallback done) {
  enqueue({true, index, sub, {}, std::move(done)});
}

void SdoClient::download(std::uint16_t index, std::uint8_t sub, std::vector<std::uint8_t> data,
                         SdoCallback done) {
  enqueue({false, index, sub, std::move(data), std::move(done)});
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
  if (r.upload) {
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
  if (f.data[0] == kAbort) {
    // The server has one transfer with us, so its abort ends the active one
    // even when it names another object (some servers send zeros), unless
    // it names the object of a transfer we gave up on: that one is late.
    if (!initiate_matches(f) && multiplexer(f) == given_up_) return true;
    finish({static_cast<SdoAbort>(load_le<std::uint32_t>(std::span(f.data).subspan(4))), true, {}});
    return true;
  }
  // A response that names another object is a late answer to an older
  // transfer, whatever its kind: checked before the command specifier.
  if (carries_multiplexer(f) && !initiate_matches(f)) return true;
  const bool initiating = phase_ == Phase::kDownloadInitiate || phase_ == Phase::kUploadInitiate;
  if (!initiating && carries_multiplexer(f)) return true;  // a repeated initiate answer
  if (active_->upload)
    on_upload_response(f);
  else
    on_download_response(f);
  return true;
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
