// SPDX-License-Identifier: GPL-2.0
#include "advee/canopen/sim/lss_slave.hpp"

#include "advee/byte_order.hpp"
#include "advee/canopen/nmt.hpp"

namespace advee::canopen::sim {

LssSlave::LssSlave(LssAddress address, std::uint8_t stored_node_id, FrameSender send,
                   std::function<void()> reset_communication)
    : address_(address), send_(std::move(send)), reset_communication_(std::move(reset_communication)),
      stored_(stored_node_id) {}

void LssSlave::power_on() {
  pending_ = stored_;
  pending_bit_timing_ = stored_bit_timing_;
  reset_communication();
}

void LssSlave::reset_communication() {
  active_ = pending_;
  mode_ = LssMode::kWaiting;
  fastscan_sub_ = 0;
}

void LssSlave::answer(std::uint8_t cs, std::uint32_t word, std::uint8_t b5) {
  if (faults_.silent) return;
  CanFrame f;
  f.id = cob::kLssSlave;
  f.len = 8;
  f.data[0] = cs;
  store_le<std::uint32_t>(std::span<std::uint8_t>(f.data).subspan(1, 4), word);
  f.data[5] = b5;
  send_(f);
}

bool LssSlave::handle(const CanFrame& f) {
  if (f.id != cob::kLssMaster || f.rtr) return false;
  if (f.len != 8) return true;  // CiA 305 frames have 8 bytes; others are not LSS
  const std::uint8_t cs = f.data[0];
  if (cs == lss_cs::kSwitchGlobal) {
    if (f.data[1] == static_cast<std::uint8_t>(LssMode::kWaiting)) {
      const bool got_node_id = mode_ == LssMode::kConfiguration && active_ == kLssUnconfigured &&
                               pending_ != kLssUnconfigured;
      mode_ = LssMode::kWaiting;
      selected_ = {};
      // CiA 305: a node that had no node-ID and got one starts (NMT reset
      // communication) as soon as it is back in waiting state.
      if (got_node_id && reset_communication_) reset_communication_();
    } else if (f.data[1] == static_cast<std::uint8_t>(LssMode::kConfiguration)) {
      mode_ = LssMode::kConfiguration;
    }
    return true;
  }
  if (cs == lss_cs::kIdentifyNonConfigured) {
    if (unconfigured()) answer(lss_cs::kIdentifyNonConfiguredAnswer);
    return true;
  }
  if (mode_ == LssMode::kWaiting)
    on_waiting(f);
  else
    on_configuration(f);
  return true;
}

void LssSlave::on_waiting(const CanFrame& f) {
  const std::uint8_t cs = f.data[0];
  const auto word = load_le<std::uint32_t>(f.payload().subspan(1, 4));
  if (cs >= lss_cs::kSwitchSelectiveVendor && cs <= lss_cs::kSwitchSelectiveVendor + 3) {
    const unsigned i = cs - lss_cs::kSwitchSelectiveVendor;
    selected_.words[i] = word;
    // The serial number comes last and completes the address.
    if (i == 3 && selected_ == address_) {
      mode_ = LssMode::kConfiguration;
      answer(lss_cs::kSwitchSelectiveAnswer);
    }
    return;
  }
  if (cs == lss_cs::kFastscan) on_fastscan(f);
}

void LssSlave::on_fastscan(const CanFrame& f) {
  // Only nodes without node-ID take part (as CANopenNode's slave does):
  // the fastscan is how they get one.
  if (!unconfigured()) return;
  const auto id = load_le<std::uint32_t>(f.payload().subspan(1, 4));
  const std::uint8_t bit = f.data[5], sub = f.data[6], next = f.data[7];
  if (bit == kFastscanReset) {
    fastscan_sub_ = 0;
    answer(lss_cs::kIdentifySlave);
    return;
  }
  if (bit > 31 || sub > 3 || next > 3 || sub != fastscan_sub_) return;
  const std::uint32_t mask = ~0u << bit;
  if ((address_.words[sub] & mask) != (id & mask)) return;
  fastscan_sub_ = next;
  // The whole address matched: the confirm of the last word wraps around.
  if (bit == 0 && next < sub) mode_ = LssMode::kConfiguration;
  answer(lss_cs::kIdentifySlave);
}

void LssSlave::on_configuration(const CanFrame& f) {
  const std::uint8_t cs = f.data[0];
  switch (cs) {
    case lss_cs::kConfigureNodeId: {
      const std::uint8_t id = f.data[1];
      const bool ok = is_valid_node_id(id) || id == kLssUnconfigured;
      if (ok) pending_ = id;
      answer(cs, ok ? 0 : 1);
      break;
    }
    case lss_cs::kConfigureBitTiming: {
      const std::uint8_t selector = f.data[1], index = f.data[2];
      // Selector 0 is the CiA 301 table; automatic detection (9) is not
      // something a simulated bus has.
      const bool ok = selector == 0 && index != 9 && lss_bit_rate_kbit(index).has_value();
      if (ok) pending_bit_timing_ = index;
      answer(cs, ok ? 0 : 1);
      break;
    }
    case lss_cs::kActivateBitTiming:
      activated_delay_ms_ = static_cast<std::uint16_t>(f.data[1] | (f.data[2] << 8));
      break;
    case lss_cs::kStore:
      if (faults_.store_unsupported) {
        answer(cs, 1);
      } else if (faults_.store_fails) {
        answer(cs, 2);
      } else {
        stored_ = pending_;
        stored_bit_timing_ = pending_bit_timing_;
        answer(cs, 0);
      }
      break;
    case lss_cs::kInquireNodeId: answer(cs, active_); break;
    default:
      if (cs >= lss_cs::kInquireVendor && cs < lss_cs::kInquireNodeId)
        answer(cs, address_.words[cs - lss_cs::kInquireVendor]);
      break;
  }
}

LssAddress LssSimNode::identity_of(const DriveSimConfig& cfg, const NowFn& now) {
  // The drive's own 0x1018 is the LSS address; a drive that is never
  // powered on sends nothing.
  SimulatedDrive probe(cfg, [](const CanFrame&) {}, now);
  LssAddress a;
  for (std::uint8_t i = 0; i < 4; ++i) a.words[i] = probe.od().get<std::uint32_t>(0x1018, i + 1);
  return a;
}

LssSimNode::LssSimNode(DriveSimConfig cfg, std::uint8_t stored_node_id, FrameSender send, NowFn now)
    : cfg_(cfg), send_(std::move(send)), now_(std::move(now)),
      lss_(identity_of(cfg, now_), stored_node_id, send_, [this] { start(); }) {}

void LssSimNode::power_on() {
  lss_.power_on();
  if (lss_.active_node_id() != kLssUnconfigured) start();
}

// Reset communication with the pending node-ID: a new drive for it, or none
// when the node-ID was taken away.
void LssSimNode::start() {
  lss_.reset_communication();
  drive_.reset();
  const std::uint8_t id = lss_.active_node_id();
  if (id == kLssUnconfigured) {
    if (on_start_) on_start_(id);
    return;
  }
  DriveSimConfig c = cfg_;
  c.node = id;
  drive_ = std::make_unique<SimulatedDrive>(c, send_, now_);
  drive_->power_on();
  if (on_start_) on_start_(id);
}

void LssSimNode::handle(const CanFrame& f) {
  if (lss_.handle(f)) return;
  if (!drive_) return;
  if (f.id == cob::kNmt && f.len == 2 && (f.data[1] == 0 || f.data[1] == lss_.active_node_id()) &&
      lss_.pending_node_id() != lss_.active_node_id()) {
    const auto cmd = static_cast<NmtCommand>(f.data[0]);
    if (cmd == NmtCommand::kResetCommunication || cmd == NmtCommand::kResetNode) return start();
  }
  drive_->handle(f);
}

void LssSimNode::poll() {
  if (drive_) drive_->poll();
}

std::optional<TimePoint> LssSimNode::deadline() const {
  if (drive_) return drive_->deadline();
  return std::nullopt;
}

}  // namespace advee::canopen::sim
