// SPDX-License-Identifier: GPL-2.0
#include "advee/rs485/frame_codec.hpp"

#include <stdexcept>

#include "advee/crc8_maxim.hpp"

namespace advee::rs485 {

std::vector<std::uint8_t> encode_ldisc_frame(const Frame& frame) {
  if (frame.data.size() > kMaxData) throw std::length_error("rs485 frame: more than 255 data bytes");
  std::vector<std::uint8_t> out;
  out.reserve(kHeaderLength + frame.data.size());
  out.push_back(frame.addr);
  out.push_back(frame.instr);
  out.push_back(frame.flags);
  out.push_back(static_cast<std::uint8_t>(frame.data.size()));
  out.insert(out.end(), frame.data.begin(), frame.data.end());
  return out;
}

Expected<Frame> decode_ldisc_frame(std::span<const std::uint8_t> bytes) {
  if (bytes.size() < kHeaderLength || bytes.size() != kHeaderLength + bytes[3]) return Outcome::bad_response;
  return Frame{bytes[0], bytes[1], bytes[2], {bytes.begin() + kHeaderLength, bytes.end()}};
}

std::vector<std::uint8_t> encode_wire_frame(const Frame& frame) {
  auto out = encode_ldisc_frame(frame);
  out.push_back(crc8_maxim(out));
  return out;
}

void WireParser::reset() {
  state_ = State::idle;
  bytes_.clear();
}

WireParser::Result WireParser::feed(std::uint8_t byte, bool ninth_bit) {
  if (ninth_bit) {
    if (state_ != State::idle) ++truncated_;
    bytes_.assign(1, byte);
    state_ = State::header;
    return Result::incomplete;
  }
  switch (state_) {
    case State::idle:
      return Result::noise;
    case State::header:
      bytes_.push_back(byte);
      if (bytes_.size() == kHeaderLength) state_ = bytes_[3] ? State::data : State::crc;
      return Result::incomplete;
    case State::data:
      bytes_.push_back(byte);
      if (bytes_.size() == kHeaderLength + bytes_[3]) state_ = State::crc;
      return Result::incomplete;
    case State::crc:
      break;
  }
  state_ = State::idle;
  if (crc8_maxim(bytes_) != byte) return Result::bad_crc;
  frame_ = Frame{bytes_[0], bytes_[1], bytes_[2], {bytes_.begin() + kHeaderLength, bytes_.end()}};
  return Result::frame;
}

}  // namespace advee::rs485
