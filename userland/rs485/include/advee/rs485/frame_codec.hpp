// SPDX-License-Identifier: GPL-2.0
// Frame codecs. Two representations exist:
//  - the line discipline's (ADDR INSTR FLAGS LEN DATA, no CRC): read()/write();
//  - the wire's (the same plus CRC-8/MAXIM; the 9th bit is 1 on ADDR only),
//    which a simulated slave speaks on /dev/ts7800-sim/uartN.
// Decoding never trusts a length: a frame that does not add up is an error.
#pragma once

#include <cstdint>
#include <optional>
#include <span>
#include <system_error>
#include <vector>

#include "advee/rs485/error.hpp"
#include "advee/rs485/protocol.hpp"

namespace advee::rs485 {

// ADDR INSTR FLAGS LEN DATA (no CRC). Throws std::length_error above 255 data bytes.
std::vector<std::uint8_t> encode_ldisc_frame(const Frame& frame);
// Parses exactly one frame of that form; Outcome::bad_response if the buffer
// is shorter than 4 bytes or LEN does not match its length.
Expected<Frame> decode_ldisc_frame(std::span<const std::uint8_t> bytes);

// ADDR INSTR FLAGS LEN DATA CRC, the bytes as they go on the wire (the first
// one with the 9th bit set). Throws std::length_error above 255 data bytes.
std::vector<std::uint8_t> encode_wire_frame(const Frame& frame);

// Receiver of wire characters (a slave's or a sniffer's view of the bus):
// feed every character with its 9th bit; a character with the 9th bit set
// starts a new frame (resynchronisation), as the spec requires.
class WireParser {
 public:
  enum class Result { incomplete, frame, bad_crc, noise };
  // After Result::frame, frame() holds the frame (CRC checked and stripped).
  Result feed(std::uint8_t byte, bool ninth_bit);
  const Frame& frame() const { return frame_; }
  // The frame in progress was cut short by a new address character.
  std::uint64_t truncated() const { return truncated_; }
  void reset();

 private:
  enum class State { idle, header, data, crc };
  State state_ = State::idle;
  std::vector<std::uint8_t> bytes_;  // ADDR INSTR FLAGS LEN DATA so far
  Frame frame_;
  std::uint64_t truncated_ = 0;
};

}  // namespace advee::rs485
