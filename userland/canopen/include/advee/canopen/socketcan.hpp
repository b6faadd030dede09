// SPDX-License-Identifier: GPL-2.0
// SocketCAN transport: a non-blocking CAN_RAW socket that also receives error
// frames (decoded into the controller state) and the kernel's count of frames
// dropped for this socket (SO_RXQ_OVFL). canopen-notes.md §3.15.
#pragma once

#include <cstdint>
#include <optional>
#include <string>
#include <variant>
#include <vector>

#include "advee/canopen/frame.hpp"
#include "advee/unique_fd.hpp"

struct can_frame;

namespace advee::canopen {

enum class CanControllerState { kErrorActive, kErrorWarning, kErrorPassive, kBusOff };
std::string_view to_string(CanControllerState s);

struct CanErrorInfo {
  std::optional<CanControllerState> state;  // set if the frame reports a state change
  bool restarted = false;                   // controller restarted after bus-off
  bool tx_timeout = false;
  bool lost_arbitration = false;
  bool protocol_violation = false;
  bool no_ack = false;
  bool bus_error = false;
  bool rx_overflow = false;
  bool tx_overflow = false;
  std::uint8_t tx_errors = 0;  // counters, when the driver reports them
  std::uint8_t rx_errors = 0;
};

// Decodes a kernel error frame (CAN_ERR_FLAG set) per linux/can/error.h.
CanErrorInfo decode_error_frame(const ::can_frame& f);

class CanSocket {
 public:
  // Throws std::system_error (e.g. ENODEV for an unknown interface).
  static CanSocket open(const std::string& ifname);

  enum class SendStatus { kSent, kRetryLater, kFailed };
  // kRetryLater on ENOBUFS/EAGAIN (TX queue full: back off and resend).
  SendStatus send(const CanFrame& f);

  struct Error {
    CanErrorInfo info;
  };
  using Received = std::variant<CanFrame, Error>;
  // nullopt when nothing is pending (EAGAIN). Throws on real errors.
  std::optional<Received> receive();
  // Reads up to `max` (at most 64) pending messages with one recvmmsg() and
  // appends the classic frames and error frames to `out`. Returns how many
  // messages were read: 0 when nothing is pending, `max` when more may be.
  std::size_t receive_batch(std::vector<Received>& out, std::size_t max);

  int fd() const { return fd_.get(); }
  // Frames the kernel dropped for this socket because its queue was full.
  std::uint32_t dropped() const { return dropped_; }
  const std::string& interface() const { return ifname_; }

 private:
  CanSocket(UniqueFd fd, std::string ifname) : fd_(std::move(fd)), ifname_(std::move(ifname)) {}
  UniqueFd fd_;
  std::string ifname_;
  std::uint32_t dropped_ = 0;
};

}  // namespace advee::canopen
