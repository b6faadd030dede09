// SPDX-License-Identifier: GPL-2.0
#include "advee/rs485/bus.hpp"

#include <fcntl.h>
#include <linux/n_rs485.h>
#include <poll.h>
#include <sys/eventfd.h>
#include <sys/ioctl.h>
#include <unistd.h>

#include <array>
#include <cerrno>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <limits>

#include "advee/rs485/frame_codec.hpp"

namespace advee::rs485 {

// protocol.hpp mirrors the UAPI without including it; keep both in step.
static_assert(kBroadcast == N_RS485_ADDR_BROADCAST);
static_assert(kMaxData == N_RS485_MAX_DATA);
static_assert(kHeaderLength == N_RS485_HEADER_LEN);
static_assert(request_flag::kResend == N_RS485_REQ_RESEND && request_flag::kNoAck == N_RS485_REQ_NOACK);
static_assert(response_flag::kAck == N_RS485_RESP_ACK && response_flag::kUnknownInstruction == N_RS485_RESP_UNKINSTR &&
              response_flag::kDeviceError == N_RS485_RESP_DEVERR && response_flag::kEvent == N_RS485_RESP_EVENT);
static_assert(static_cast<int>(Outcome::ok) == N_RS485_OK && static_cast<int>(Outcome::timeout) == N_RS485_TIMEOUT &&
              static_cast<int>(Outcome::bad_crc) == N_RS485_BADCRC &&
              static_cast<int>(Outcome::unknown_instruction) == N_RS485_UNKINSTR &&
              static_cast<int>(Outcome::device_error) == N_RS485_DEVERR && static_cast<int>(Outcome::error) == N_RS485_ERROR);
static_assert(static_cast<int>(NodeState::active) == N_RS485_NODE_ACTIVE &&
              static_cast<int>(NodeState::passive) == N_RS485_NODE_PASSIVE &&
              static_cast<int>(NodeState::off) == N_RS485_NODE_OFF);

namespace {

std::error_code last_error() { return {errno, std::system_category()}; }

// After another process detached n_rs485, the tty's new discipline does not
// know the ioctls of this one (ENOTTY): report that as "not connected".
std::error_code ioctl_error() {
  if (errno == ENOTTY) return std::make_error_code(std::errc::not_connected);
  return last_error();
}

// How often the event thread checks that the discipline is still attached:
// a detach wakes poll() only while it is in progress, after which the new
// discipline's poll() reports nothing, so it is noticed by this check.
constexpr int kDetachCheckMs = 500;

[[noreturn]] void throw_errno(const std::string& what) { throw std::system_error(last_error(), what); }
[[noreturn]] void throw_ioctl(const std::string& what) { throw std::system_error(ioctl_error(), what); }

// ioctl() restarted on EINTR: only for the ioctls that are idempotent
// (configuration, statistics, node state), never for a transaction.
int ioctl_retry(int fd, unsigned long request, void* arg) {
  int ret;
  do ret = ::ioctl(fd, request, arg);
  while (ret < 0 && errno == EINTR);
  return ret;
}

// Microseconds for the kernel, or N_RS485_DEFAULT; nullopt if not representable
// (the kernel checks the range itself and answers EINVAL).
std::optional<std::uint32_t> to_timeout_us(const std::optional<std::chrono::microseconds>& t) {
  if (!t) return N_RS485_DEFAULT;
  if (t->count() < 0 || t->count() >= static_cast<std::int64_t>(N_RS485_DEFAULT)) return std::nullopt;
  return static_cast<std::uint32_t>(t->count());
}

}  // namespace

std::string_view node_state_name(NodeState s) noexcept {
  switch (s) {
    case NodeState::active: return "active";
    case NodeState::passive: return "passive";
    case NodeState::off: return "off";
  }
  return "?";
}

std::string Bus::resolve_device(const std::string& device) {
  if (device.find('/') != std::string::npos) return device;
  return "/dev/rs485/" + device;
}

int Bus::default_ldisc() {
  std::ifstream in("/sys/module/n_rs485/parameters/ldisc");
  int n = 0;
  if (in >> n && n > 0) return n;
  return N_RS485_DEFAULT_LDISC;
}

Bus::Bus(const std::string& device, const BusOptions& options)
    : device_(resolve_device(device)), ldisc_(options.ldisc.value_or(default_ldisc())) {
  // O_NONBLOCK: open does not wait for carrier, read_event() does not block.
  // Transactions (ioctl) block regardless.
  fd_.reset(::open(device_.c_str(), O_RDWR | O_NOCTTY | O_NONBLOCK | O_CLOEXEC));
  if (!fd_) throw_errno("open " + device_);
  int current = -1;
  if (ioctl_retry(fd_.get(), TIOCGETD, &current) < 0) throw_errno(device_ + ": TIOCGETD (not a tty?)");
  // Setting the number it already has would end other processes' pending calls.
  if (current != ldisc_) {
    int ld = ldisc_;
    if (ioctl_retry(fd_.get(), TIOCSETD, &ld) < 0) {
      // EINVAL: no discipline of that number is registered (the kernel's
      // request_module("tty-ldisc-N") found none).
      const std::error_code error = last_error();
      std::string what = device_ + ": attach line discipline " + std::to_string(ldisc_) + " (n_rs485)";
      if (error.value() == EINVAL)
        what += std::filesystem::exists("/sys/module/n_rs485")
                    ? ": the kernel has no discipline " + std::to_string(ldisc_) +
                          " (n_rs485 is loaded with another ldisc= number)"
                    : ": n_rs485 is not loaded and could not be loaded (modprobe n_rs485)";
      throw std::system_error(error, what);
    }
  }
  stop_.reset(::eventfd(0, EFD_CLOEXEC | EFD_NONBLOCK));
  if (!stop_) throw_errno("eventfd");
  if (options.config) set_config(*options.config);
}

Bus::~Bus() {
  std::lock_guard lock(thread_mutex_);
  if (thread_.joinable()) {
    const std::uint64_t one = 1;
    // An eventfd write of 1 cannot fail short of a counter overflow.
    [[maybe_unused]] auto n = ::write(stop_.get(), &one, sizeof(one));
    thread_.join();
  }
}

Result Bus::transact(const Request& request) {
  Result result;
  const auto timeout = to_timeout_us(request.options.timeout);
  if (request.data.size() > kMaxData || !timeout ||
      (request.options.retries && *request.options.retries >= N_RS485_DEFAULT)) {
    result.error = std::make_error_code(std::errc::invalid_argument);
    return result;
  }
  n_rs485_xfer x;
  std::memset(&x, 0, sizeof(x));
  x.req.addr = request.addr;
  x.req.instr = request.instr;
  x.req.flags = request.no_ack ? N_RS485_REQ_NOACK : 0;
  x.req.len = static_cast<std::uint8_t>(request.data.size());
  std::memcpy(x.req.data, request.data.data(), request.data.size());
  x.timeout_us = *timeout;
  x.retries = request.options.retries.value_or(N_RS485_DEFAULT);
  // Not restarted on EINTR: the request may have executed.
  if (::ioctl(fd_.get(), N_RS485_IOC_XFER, &x) < 0) {
    result.error = ioctl_error();
    return result;
  }
  result.attempts = x.attempts;
  result.flags = x.resp.flags;
  result.data.assign(x.resp.data, x.resp.data + x.resp.len);
  if (x.status != N_RS485_OK) {
    result.error = x.status <= N_RS485_ERROR ? make_error_code(static_cast<Outcome>(x.status))
                                           : make_error_code(Outcome::error);
  }
  return result;
}

std::error_code Bus::send_raw(const Frame& frame) {
  if (frame.data.size() > kMaxData) return std::make_error_code(std::errc::invalid_argument);
  const auto bytes = encode_ldisc_frame(frame);
  ssize_t n;
  do n = ::write(fd_.get(), bytes.data(), bytes.size());
  while (n < 0 && errno == EINTR);
  if (n < 0) return last_error();
  if (static_cast<std::size_t>(n) != bytes.size()) return std::make_error_code(std::errc::io_error);
  return {};
}

std::optional<Frame> Bus::read_event() {
  std::array<std::uint8_t, N_RS485_MAX_FRAME + 1> buf;
  ssize_t n;
  do n = ::read(fd_.get(), buf.data(), buf.size());
  while (n < 0 && errno == EINTR);
  if (n < 0) {
    if (errno == EAGAIN) return std::nullopt;
    throw_errno(device_ + ": read event");
  }
  if (n == 0) throw std::system_error(std::make_error_code(std::errc::io_error), device_ + ": hung up");
  auto frame = decode_ldisc_frame(std::span(buf.data(), static_cast<std::size_t>(n)));
  if (!frame) throw std::system_error(frame.error(), device_ + ": event frame");
  return std::move(*frame);
}

Subscription Bus::subscribe(EventHandler on_event, ClosedHandler on_closed) {
  auto sub = events_.subscribe(std::move(on_event), std::move(on_closed));
  if (sub) start_event_thread();
  return sub;
}

void Bus::start_event_thread() {
  std::lock_guard lock(thread_mutex_);
  if (!thread_.joinable()) thread_ = std::thread([this] { event_thread_main(); });
}

void Bus::event_thread_main() {
  auto still_attached = [this](std::error_code& why) {
    int current = -1;
    if (ioctl_retry(fd_.get(), TIOCGETD, &current) < 0) {
      why = last_error();
      return false;
    }
    if (current != ldisc_) {
      why = std::make_error_code(std::errc::not_connected);
      return false;
    }
    return true;
  };
  std::error_code end;
  for (;;) {
    std::array<pollfd, 2> fds{{{fd_.get(), POLLIN, 0}, {stop_.get(), POLLIN, 0}}};
    const int n = ::poll(fds.data(), fds.size(), kDetachCheckMs);
    if (n < 0) {
      if (errno == EINTR) continue;
      end = last_error();
      break;
    }
    if (fds[1].revents) return;  // destructor: no on_closed
    if (fds[0].revents & POLLNVAL) {
      end = std::make_error_code(std::errc::bad_file_descriptor);
      break;
    }
    // Timeout: the periodic check for a detach by another process.
    if (n == 0) {
      if (!still_attached(end)) break;
      continue;
    }
    bool got = false;
    try {
      while (auto frame = read_event()) {
        got = true;
        events_.dispatch(*frame);
      }
    } catch (const std::system_error& e) {
      // EIO: hangup or detach in progress; a bad frame: n_tty's bytes.
      if (still_attached(end)) end = e.code();
      break;
    }
    if (got) continue;
    if (!still_attached(end)) break;
    if (fds[0].revents & (POLLHUP | POLLERR)) {
      end = std::make_error_code(std::errc::io_error);
      break;
    }
  }
  events_.close(end);
}

BusConfig Bus::config() const {
  n_rs485_config c{};
  if (ioctl_retry(fd_.get(), N_RS485_IOC_GET_CONFIG, &c) < 0) throw_ioctl(device_ + ": get config");
  return BusConfig{c.baud, std::chrono::microseconds(c.timeout_us), c.retries, c.gap_chars};
}

void Bus::set_config(const BusConfig& config) {
  n_rs485_config c{};
  if (ioctl_retry(fd_.get(), N_RS485_IOC_GET_CONFIG, &c) < 0) throw_ioctl(device_ + ": get config");
  const auto timeout = to_timeout_us(config.timeout);
  if (!timeout)
    throw std::system_error(std::make_error_code(std::errc::invalid_argument), device_ + ": timeout out of range");
  c.baud = config.baud;
  c.timeout_us = *timeout;
  c.retries = config.retries;
  c.gap_chars = config.gap_chars;
  if (ioctl_retry(fd_.get(), N_RS485_IOC_SET_CONFIG, &c) < 0) throw_ioctl(device_ + ": set config");
}

BusStats Bus::stats() const {
  n_rs485_stats s{};
  if (ioctl_retry(fd_.get(), N_RS485_IOC_GET_STATS, &s) < 0) throw_ioctl(device_ + ": get statistics");
  BusStats b;
  b.tx_frames = s.tx_frames;
  b.tx_bytes = s.tx_bytes;
  b.rx_frames = s.rx_frames;
  b.rx_bytes = s.rx_bytes;
  b.rx_crc_errors = s.rx_crc_errors;
  b.rx_truncated = s.rx_truncated;
  b.rx_noise = s.rx_noise;
  b.rx_overruns = s.rx_overruns;
  b.rx_framing = s.rx_framing;
  b.xfers = s.xfers;
  b.xfers_ok = s.xfers_ok;
  b.xfers_failed = s.xfers_failed;
  b.timeouts = s.timeouts;
  b.retries = s.retries;
  b.events = s.events;
  b.events_dropped = s.events_dropped;
  b.unexpected = s.unexpected;
  return b;
}

NodeStatus Bus::node(std::uint8_t addr) const {
  n_rs485_node n{};
  n.addr = addr;
  if (ioctl_retry(fd_.get(), N_RS485_IOC_GET_NODE, &n) < 0) throw_ioctl(device_ + ": get node state");
  const auto state = n.state <= N_RS485_NODE_OFF ? static_cast<NodeState>(n.state) : NodeState::off;
  return NodeStatus{addr, state, n.errors};
}

void Bus::reset_node(std::uint8_t addr) {
  n_rs485_node n{};
  n.addr = addr;
  if (ioctl_retry(fd_.get(), N_RS485_IOC_RESET_NODE, &n) < 0) throw_ioctl(device_ + ": reset node state");
}

}  // namespace advee::rs485
