// SPDX-License-Identifier: GPL-2.0
// The CiA 305 LSS slave of the simulated drives, and a simulated node that
// puts it in front of a SimulatedDrive. Passive like the drive: handle(),
// poll(), deadline().
#pragma once

#include <cstdint>
#include <functional>
#include <memory>
#include <optional>

#include "advee/canopen/clock.hpp"
#include "advee/canopen/frame.hpp"
#include "advee/canopen/lss.hpp"
#include "advee/canopen/sim/drive_sim.hpp"

namespace advee::canopen::sim {

struct LssSlaveFaults {
  bool silent = false;          // answers nothing (a node without LSS)
  bool store_unsupported = false;  // store answers error code 1
  bool store_fails = false;        // store answers error code 2 (storage media)
};

// The LSS state machine (waiting / configuration) and its services. The
// node it belongs to owns the node-ID: the active one is what the node runs
// with, the pending one what configure node-ID set (active after the node's
// next reset communication), the stored one what it boots with.
class LssSlave {
 public:
  // `stored_node_id` 1..127 or kLssUnconfigured; `reset_communication` is
  // called when a node without node-ID got one and was switched back to
  // waiting: it must reset communication (boot with pending_node_id()).
  LssSlave(LssAddress address, std::uint8_t stored_node_id, FrameSender send, std::function<void()> reset_communication);

  // True for LSS requests (0x7E5), handled or not.
  bool handle(const CanFrame& f);
  // Power-on and NMT reset communication: the pending node-ID becomes the
  // active one (power-on: the stored one first).
  void power_on();
  void reset_communication();

  LssMode mode() const { return mode_; }
  std::uint8_t active_node_id() const { return active_; }
  std::uint8_t pending_node_id() const { return pending_; }
  std::uint8_t stored_node_id() const { return stored_; }
  std::uint8_t pending_bit_timing() const { return pending_bit_timing_; }
  std::uint8_t stored_bit_timing() const { return stored_bit_timing_; }
  // Switch delay of the last activate bit timing, if any came.
  std::optional<std::uint16_t> activated_delay_ms() const { return activated_delay_ms_; }
  const LssAddress& address() const { return address_; }
  LssSlaveFaults& faults() { return faults_; }

 private:
  bool unconfigured() const { return active_ == kLssUnconfigured && pending_ == kLssUnconfigured; }
  void answer(std::uint8_t cs, std::uint32_t word = 0, std::uint8_t b5 = 0);
  void on_waiting(const CanFrame& f);
  void on_configuration(const CanFrame& f);
  void on_fastscan(const CanFrame& f);

  LssAddress address_;
  FrameSender send_;
  std::function<void()> reset_communication_;
  LssMode mode_ = LssMode::kWaiting;
  std::uint8_t stored_;
  std::uint8_t active_ = kLssUnconfigured;
  std::uint8_t pending_ = kLssUnconfigured;
  std::uint8_t pending_bit_timing_ = 0;  // CiA 301 table index (1000 kbit/s)
  std::uint8_t stored_bit_timing_ = 0;
  std::optional<std::uint16_t> activated_delay_ms_;
  LssAddress selected_;           // switch state selective: words latched so far
  std::uint8_t fastscan_sub_ = 0;  // the word this slave's fastscan is at
  LssSlaveFaults faults_;
};

// A simulated drive behind an LSS slave. Without a node-ID (stored node-ID
// kLssUnconfigured) it answers LSS only; once one is configured and the
// node is switched back to waiting, it boots with it (boot-up message) as
// CiA 305 says. A node-ID configured on a node that has one takes effect at
// its next NMT reset communication or reset node: the drive is then built
// anew with the new node-ID (its application state starts over too, which
// only matters to a simulation that renumbers a running drive).
class LssSimNode {
 public:
  // The LSS address is the drive's 0x1018 (set its serial number in cfg to
  // tell nodes of one profile apart); cfg.node is ignored.
  LssSimNode(DriveSimConfig cfg, std::uint8_t stored_node_id, FrameSender send, NowFn now);

  void power_on();
  void handle(const CanFrame& f);
  void poll();
  std::optional<TimePoint> deadline() const;

  LssSlave& lss() { return lss_; }
  // Null while the node has no node-ID.
  SimulatedDrive* drive() { return drive_.get(); }
  // Called after each reset communication with the node-ID it brought:
  // the new drive's, or kLssUnconfigured when the drive is gone (tools print
  // it, and must take drive() anew).
  void set_on_start(std::function<void(std::uint8_t)> cb) { on_start_ = std::move(cb); }

 private:
  void start();
  static LssAddress identity_of(const DriveSimConfig& cfg, const NowFn& now);

  DriveSimConfig cfg_;
  FrameSender send_;
  NowFn now_;
  LssSlave lss_;
  std::unique_ptr<SimulatedDrive> drive_;
  std::function<void(std::uint8_t)> on_start_;
};

}  // namespace advee::canopen::sim
