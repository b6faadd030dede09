// SPDX-License-Identifier: GPL-2.0
// The slave's side of the wire protocol (shared/specs/rs485-protocol.md) on
// the simulated FPGA's wire words (linux/ts7800_sim.h): 16-bit words, bits
// 7..0 the character, bit 8 the 9th bit (1 on a frame's ADDR only).
#pragma once

#include <cstddef>
#include <cstdint>
#include <functional>
#include <span>
#include <vector>

namespace advee::rs485sim {

inline constexpr std::uint16_t kWordData = 0x00ff;
inline constexpr std::uint16_t kWordBit9 = 0x0100;
inline constexpr std::uint16_t kWordBreak = 0x0200;
inline constexpr std::uint16_t kWordFrameError = 0x0400;

inline constexpr std::uint8_t kBroadcast = 0xff;

// Request flags (master to slave) and response flags (slave to master).
inline constexpr std::uint8_t kReqResend = 0x01;
inline constexpr std::uint8_t kReqNoAck = 0x02;
inline constexpr std::uint8_t kRespAck = 0x01;
inline constexpr std::uint8_t kRespUnkInstr = 0x02;
inline constexpr std::uint8_t kRespDevErr = 0x04;
inline constexpr std::uint8_t kRespEvent = 0x08;

// Standard instructions of every device.
inline constexpr std::uint8_t kInstrGetFwVersion = 0xfe;
inline constexpr std::uint8_t kInstrReset = 0xff;

// One frame without its CRC.
struct Frame {
  std::uint8_t addr = 0;
  std::uint8_t instr = 0;
  std::uint8_t flags = 0;
  std::vector<std::uint8_t> data;  // at most 255 bytes

  bool operator==(const Frame&) const = default;
};

// The frame as wire words, CRC appended; crc_xor != 0 corrupts the CRC.
std::vector<std::uint16_t> encode_words(const Frame& f, std::uint8_t crc_xor = 0);

// Counters of what the receiver threw away.
struct ReceiverStats {
  std::uint64_t frames = 0;     // complete frames with a good CRC
  std::uint64_t crc_errors = 0;
  std::uint64_t truncated = 0;  // cut short by an address character or a break
  std::uint64_t noise = 0;      // characters outside any frame
  std::uint64_t line_errors = 0;  // break or bad stop bit inside a frame
};

// Receive state machine: feed it every word read from the wire; it calls the
// sink with each complete frame whose CRC is good. A word with the 9th bit
// set always starts a new frame (resynchronisation); data characters before
// the first address character are noise.
class Receiver {
 public:
  using Sink = std::function<void(const Frame&)>;
  explicit Receiver(Sink sink) : sink_(std::move(sink)) {}

  void feed(std::uint16_t word);
  void feed(std::span<const std::uint16_t> words) {
    for (auto w : words) feed(w);
  }
  const ReceiverStats& stats() const { return stats_; }

 private:
  enum class State { kIdle, kInstr, kFlags, kLen, kData, kCrc };
  void abort_frame();

  Sink sink_;
  State state_ = State::kIdle;
  Frame cur_;
  std::size_t want_ = 0;
  ReceiverStats stats_;
};

}  // namespace advee::rs485sim
