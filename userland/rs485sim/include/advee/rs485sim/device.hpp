// SPDX-License-Identifier: GPL-2.0
// A simulated slave board: address, firmware version, the standard
// instructions, fault injection and counters. The four boards (devices.hpp)
// add their instruction sets and their readings.
#pragma once

#include <chrono>
#include <cstdint>
#include <functional>
#include <map>
#include <optional>
#include <random>
#include <span>
#include <stdexcept>
#include <string>
#include <vector>

#include "advee/rs485sim/wire_frame.hpp"

namespace advee::rs485sim {

using Clock = std::chrono::steady_clock;

// One kind of fault: fires on the next `once` requests, then with `probability`.
struct FaultSpec {
  double probability = 0.0;
  unsigned once = 0;
};

struct Faults {
  FaultSpec no_answer;  // the request is not heard: not executed, no response
  FaultSpec bad_crc;    // the response goes out with a wrong CRC
  FaultSpec unkinstr;   // answered UNKINSTR, nothing executed
  FaultSpec slow;       // the response starts slow_delay late
  std::chrono::microseconds slow_delay{std::chrono::milliseconds(200)};
};

struct DeviceStats {
  std::uint64_t requests = 0;    // frames addressed to this device (broadcasts included)
  std::uint64_t executed = 0;    // instructions executed
  std::uint64_t resends = 0;     // RESEND requests answered from the last response
  std::uint64_t broadcasts = 0;  // broadcast frames executed
  std::uint64_t unkinstr = 0;    // UNKINSTR answers (unknown or injected)
  std::uint64_t dropped = 0;     // injected no-answer
  std::uint64_t corrupted = 0;   // injected bad CRC
  std::uint64_t slow = 0;        // injected slow answers
  std::uint64_t events = 0;      // spontaneous event frames sent
  std::map<std::uint8_t, std::uint64_t> per_instr;  // executions per instruction
};

// Result of handling one request: what to send back and when.
struct Reply {
  Frame frame;
  std::uint8_t crc_xor = 0;  // != 0: injected bad CRC
  std::chrono::microseconds delay{0};
};

// Thrown by the control commands and the configuration on a bad value.
struct UsageError : std::runtime_error {
  using std::runtime_error::runtime_error;
};

class Device {
 public:
  using EventSink = std::function<void(const Frame&)>;

  Device(std::string type, std::uint8_t addr);
  virtual ~Device() = default;
  Device(const Device&) = delete;
  Device& operator=(const Device&) = delete;

  const std::string& type() const { return type_; }
  std::uint8_t address() const { return addr_; }
  std::string name() const;  // e.g. "sd1@0x10"

  void set_firmware(std::uint8_t major, std::uint8_t minor) { fw_ = {major, minor}; }
  void set_response_time(std::chrono::microseconds min, std::chrono::microseconds max);
  Faults& faults() { return faults_; }
  const DeviceStats& stats() const { return stats_; }
  void reset_stats() { stats_ = {}; }
  void set_event_sink(EventSink sink) { event_sink_ = std::move(sink); }
  void set_rng(std::mt19937* rng) { rng_ = rng; }

  // A request addressed to this device or broadcast. Returns the response to
  // send, if any.
  std::optional<Reply> handle(const Frame& req, Clock::time_point now);

  // Control commands of the device ("set <dev> KEY ARGS..."); throws UsageError.
  virtual void set(const std::string& key, const std::vector<std::string>& args) = 0;
  // Spontaneous events that are due (PSC1); the earliest next deadline.
  virtual void poll(Clock::time_point /*now*/) {}
  virtual std::optional<Clock::time_point> next_deadline() const { return std::nullopt; }
  // Readings and state in one line for the "show" command.
  virtual std::string show(Clock::time_point now) const = 0;

 protected:
  // The device-specific instruction set: nullopt = unknown instruction.
  // The response's flags default to ACK; the data is the response data.
  struct Result {
    std::uint8_t flags = kRespAck;
    std::vector<std::uint8_t> data;
  };
  virtual std::optional<Result> execute(std::uint8_t instr, std::span<const std::uint8_t> data,
                                        Clock::time_point now) = 0;
  // RESET: back to the power-on state (readings set from outside stay).
  virtual void reset_state(Clock::time_point now) = 0;
  void emit_event(std::uint8_t instr, std::vector<std::uint8_t> data);

 private:
  bool fires(FaultSpec& f);
  std::chrono::microseconds response_delay();

  std::string type_;
  std::uint8_t addr_;
  std::pair<std::uint8_t, std::uint8_t> fw_{1, 0};
  std::chrono::microseconds resp_min_{200}, resp_max_{2000};
  Faults faults_;
  DeviceStats stats_;
  std::optional<Frame> last_response_;
  EventSink event_sink_;
  std::mt19937* rng_ = nullptr;
};

// Helpers shared by the models and the control commands.
double parse_double(const std::string& s, const char* what);
long long parse_int(const std::string& s, const char* what, long long min, long long max);
void put_u16(std::vector<std::uint8_t>& v, std::uint16_t x);

}  // namespace advee::rs485sim
