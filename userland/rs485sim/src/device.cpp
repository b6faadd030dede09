// SPDX-License-Identifier: GPL-2.0
#include "advee/rs485sim/device.hpp"

#include <cerrno>
#include <cmath>
#include <cstdio>
#include <cstdlib>

namespace advee::rs485sim {

Device::Device(std::string type, std::uint8_t addr) : type_(std::move(type)), addr_(addr) {}

std::string Device::name() const {
  char buf[48];
  std::snprintf(buf, sizeof(buf), "%s@0x%02x", type_.c_str(), addr_);
  return buf;
}

void Device::set_response_time(std::chrono::microseconds min, std::chrono::microseconds max) {
  if (min.count() < 0 || max < min) throw UsageError("response time: need 0 <= min <= max");
  resp_min_ = min;
  resp_max_ = max;
}

bool Device::fires(FaultSpec& f) {
  if (f.once) {
    --f.once;
    return true;
  }
  if (f.probability <= 0.0 || !rng_) return false;
  return std::uniform_real_distribution<double>(0.0, 1.0)(*rng_) < f.probability;
}

std::chrono::microseconds Device::response_delay() {
  if (!rng_ || resp_min_ == resp_max_) return resp_min_;
  return std::chrono::microseconds(
      std::uniform_int_distribution<long>(resp_min_.count(), resp_max_.count())(*rng_));
}

std::optional<Reply> Device::handle(const Frame& req, Clock::time_point now) {
  ++stats_.requests;
  const bool broadcast = req.addr == kBroadcast;
  if (!broadcast && fires(faults_.no_answer)) {
    ++stats_.dropped;
    return std::nullopt;
  }

  Reply reply;
  if (req.flags & kReqResend) {
    // Never execute again: the last response, if it answered this instruction;
    // otherwise the request was never heard and the master's next try
    // (after its timeout) repeats the original request.
    if (broadcast || !last_response_ || last_response_->instr != req.instr) return std::nullopt;
    ++stats_.resends;
    reply.frame = *last_response_;
  } else if (!broadcast && fires(faults_.unkinstr)) {
    ++stats_.unkinstr;
    reply.frame = Frame{addr_, req.instr, kRespUnkInstr, {}};
  } else {
    std::optional<Result> r;
    if (req.instr == kInstrGetFwVersion) {
      r = Result{kRespAck, {fw_.first, fw_.second}};
    } else if (req.instr == kInstrReset) {
      r = Result{kRespAck, {}};
    } else {
      r = execute(req.instr, req.data, now);
    }
    if (r) {
      ++stats_.executed;
      ++stats_.per_instr[req.instr];
      if (broadcast) ++stats_.broadcasts;
      reply.frame = Frame{addr_, req.instr, r->flags, std::move(r->data)};
    } else {
      ++stats_.unkinstr;
      reply.frame = Frame{addr_, req.instr, kRespUnkInstr, {}};
    }
    // The ACK of RESET leaves before the device restarts; model the restart
    // right away (the response is already built).
    if (r && req.instr == kInstrReset) reset_state(now);
    if (!broadcast) last_response_ = reply.frame;
  }
  if (broadcast || (req.flags & kReqNoAck)) return std::nullopt;

  reply.delay = response_delay();
  if (fires(faults_.slow)) {
    ++stats_.slow;
    reply.delay += faults_.slow_delay;
  }
  if (fires(faults_.bad_crc)) {
    ++stats_.corrupted;
    reply.crc_xor = 0x5a;
  }
  return reply;
}

void Device::emit_event(std::uint8_t instr, std::vector<std::uint8_t> data) {
  if (!event_sink_) return;
  ++stats_.events;
  event_sink_(Frame{addr_, instr, kRespEvent, std::move(data)});
}

double parse_double(const std::string& s, const char* what) {
  char* end = nullptr;
  errno = 0;
  const double v = std::strtod(s.c_str(), &end);
  if (s.empty() || *end || errno || !std::isfinite(v))
    throw UsageError(std::string(what) + ": not a number: '" + s + "'");
  return v;
}

// long long: 64 bits on every target (a long is 32 bits on ARM, where a
// bound of 0xffffffff written as a long was -1 and refused every seed).
long long parse_int(const std::string& s, const char* what, long long min, long long max) {
  char* end = nullptr;
  errno = 0;
  const long long v = std::strtoll(s.c_str(), &end, 0);
  if (s.empty() || *end || errno)
    throw UsageError(std::string(what) + ": not an integer: '" + s + "'");
  if (v < min || v > max)
    throw UsageError(std::string(what) + ": " + s + " out of range " + std::to_string(min) + ".." +
                     std::to_string(max));
  return v;
}

void put_u16(std::vector<std::uint8_t>& v, std::uint16_t x) {
  v.push_back(static_cast<std::uint8_t>(x & 0xff));
  v.push_back(static_cast<std::uint8_t>(x >> 8));
}

}  // namespace advee::rs485sim
