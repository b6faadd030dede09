// SPDX-License-Identifier: GPL-2.0
#include "advee/rs485sim/wire_frame.hpp"

#include "advee/crc8_maxim.hpp"

namespace advee::rs485sim {

namespace {

std::vector<std::uint8_t> frame_bytes(const Frame& f) {
  std::vector<std::uint8_t> b{f.addr, f.instr, f.flags, static_cast<std::uint8_t>(f.data.size())};
  b.insert(b.end(), f.data.begin(), f.data.end());
  return b;
}

}  // namespace

std::vector<std::uint16_t> encode_words(const Frame& f, std::uint8_t crc_xor) {
  const auto b = frame_bytes(f);
  std::vector<std::uint16_t> w(b.begin(), b.end());
  w[0] |= kWordBit9;
  w.push_back(static_cast<std::uint16_t>(crc8_maxim(b) ^ crc_xor));
  return w;
}

void Receiver::abort_frame() {
  if (state_ != State::kIdle) ++stats_.truncated;
  state_ = State::kIdle;
}

void Receiver::feed(std::uint16_t word) {
  if (word & (kWordBreak | kWordFrameError)) {
    // A break or a character with a bad stop bit: the frame it belongs to
    // cannot be trusted; wait for the next address character.
    if (state_ != State::kIdle) ++stats_.line_errors;
    state_ = State::kIdle;
    return;
  }
  const auto c = static_cast<std::uint8_t>(word & kWordData);
  if (word & kWordBit9) {
    abort_frame();
    cur_ = Frame{};
    cur_.addr = c;
    state_ = State::kInstr;
    return;
  }
  switch (state_) {
    case State::kIdle:
      ++stats_.noise;
      return;
    case State::kInstr:
      cur_.instr = c;
      state_ = State::kFlags;
      return;
    case State::kFlags:
      cur_.flags = c;
      state_ = State::kLen;
      return;
    case State::kLen:
      want_ = c;
      state_ = want_ ? State::kData : State::kCrc;
      return;
    case State::kData:
      cur_.data.push_back(c);
      if (cur_.data.size() == want_) state_ = State::kCrc;
      return;
    case State::kCrc: {
      state_ = State::kIdle;
      std::vector<std::uint8_t> b{cur_.addr, cur_.instr, cur_.flags,
                                  static_cast<std::uint8_t>(cur_.data.size())};
      b.insert(b.end(), cur_.data.begin(), cur_.data.end());
      if (crc8_maxim(b) != c) {
        ++stats_.crc_errors;
        return;
      }
      ++stats_.frames;
      sink_(cur_);
      return;
    }
  }
}

}  // namespace advee::rs485sim
