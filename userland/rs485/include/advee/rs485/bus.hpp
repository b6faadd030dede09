// SPDX-License-Identifier: GPL-2.0
// Bus: one RS-485/EIA-422 bus master over the n_rs485 line discipline
// (docs/rs485proto.md). Opens the tty, attaches the discipline if it is not
// attached yet, and talks to it through its ioctls, read() and write().
//
//   advee::rs485::Bus bus("/dev/ttyTSU0");          // or Bus("a") = /dev/rs485/a
//   auto r = bus.transact({0x10, 0xFE});   // GET_FW_VERSION of node 0x10
//   if (r) printf("fw %u.%u\n", r.data[0], r.data[1]);
//   else   printf("%s\n", r.error.message().c_str());
//
// Every fd and the event thread are owned (RAII). The discipline stays
// attached when the Bus goes (the last close of the tty detaches it).
#pragma once

#include <atomic>
#include <chrono>
#include <cstdint>
#include <memory>
#include <mutex>
#include <optional>
#include <string>
#include <thread>

#include "advee/rs485/event_dispatcher.hpp"
#include "advee/rs485/transport.hpp"
#include "advee/unique_fd.hpp"

namespace advee::rs485 {

// Bus configuration (struct n_rs485_config). Ranges checked by the kernel:
// baud 300..4000000, timeout 100 us..10 s, retries 0..16, gap 2..255 characters.
struct BusConfig {
  std::uint32_t baud = 115200;
  std::chrono::microseconds timeout{10000};  // default response timeout
  std::uint32_t retries = 2;                 // default retries after a failure
  std::uint32_t gap_chars = 2;               // idle characters before a request
  friend bool operator==(const BusConfig&, const BusConfig&) = default;
};

// Statistics since attach (struct n_rs485_stats, same names).
struct BusStats {
  std::uint64_t tx_frames = 0, tx_bytes = 0, rx_frames = 0, rx_bytes = 0;
  std::uint64_t rx_crc_errors = 0, rx_truncated = 0, rx_noise = 0, rx_overruns = 0, rx_framing = 0;
  std::uint64_t xfers = 0, xfers_ok = 0, xfers_failed = 0, timeouts = 0, retries = 0;
  std::uint64_t events = 0, events_dropped = 0, unexpected = 0;
};

// CAN-like per-node error state: +8 per failed transaction, -1 per good one.
enum class NodeState : std::uint8_t {
  active = 0,   // counter < 128
  passive = 1,  // 128 <= counter < 256
  off = 2,      // counter >= 256: do not poll it (still served when asked)
};
std::string_view node_state_name(NodeState s) noexcept;  // "active", "passive", "off"

struct NodeStatus {
  std::uint8_t addr = 0;
  NodeState state = NodeState::active;
  std::uint32_t errors = 0;
};

struct BusOptions {
  // Applied after opening (get-modify-set: fields of the kernel structure
  // this library does not know are kept). Unset = leave as is.
  std::optional<BusConfig> config;
  // Line discipline number; unset = /sys/module/n_rs485/parameters/ldisc if
  // the module is loaded, else 29 (N_RS485_DEFAULT_LDISC).
  std::optional<int> ldisc;
};

class Bus final : public Transport {
 public:
  // `device`: a path ("/dev/ttyTSU0", "/dev/rs485/a") or a bare bus name
  // ("a" = /dev/rs485/a). Throws std::system_error (open, attach, config).
  explicit Bus(const std::string& device, const BusOptions& options = {});
  ~Bus() override;  // stops the event thread, closes the tty

  // "/dev/rs485/a" for "a", anything with a '/' unchanged.
  static std::string resolve_device(const std::string& device);
  // The discipline number BusOptions::ldisc defaults to.
  static int default_ldisc();

  const std::string& device() const { return device_; }
  int ldisc() const { return ldisc_; }

  // --- Transport ---
  // Errors of the call itself come as system errors (EINVAL: an option out
  // of range, EINTR, EIO: detached or hung up during the call, ENOTCONN: the
  // discipline is no longer attached).
  Result transact(const Request& request) override;
  // Starts the event thread on the first subscription. The thread ends (and
  // on_closed runs) on hangup (EIO), on detach of the discipline by another
  // process (ENOTCONN, noticed within 0.5 s), or on a read error; it is
  // joined by the destructor. Do not mix with read_event().
  Subscription subscribe(EventHandler on_event, ClosedHandler on_closed = {}) override;

  // Sends one raw frame with write() (no retries); a response, if any, comes
  // back as an event. EAGAIN if the request queue is full.
  std::error_code send_raw(const Frame& frame);

  // For an event loop instead of subscribe(): poll event_fd() for POLLIN,
  // then read_event() until it returns nullopt. Errors: std::system_error.
  int event_fd() const { return fd_.get(); }
  std::optional<Frame> read_event();

  // --- configuration, statistics, node state (throw std::system_error) ---
  BusConfig config() const;
  void set_config(const BusConfig& config);
  BusStats stats() const;
  NodeStatus node(std::uint8_t addr) const;
  void reset_node(std::uint8_t addr);

 private:
  void start_event_thread();
  void event_thread_main();

  std::string device_;
  int ldisc_ = 0;
  UniqueFd fd_;
  UniqueFd stop_;  // eventfd: wakes the event thread for shutdown
  EventDispatcher events_;
  std::mutex thread_mutex_;
  std::thread thread_;
};

}  // namespace advee::rs485
