// SPDX-License-Identifier: GPL-2.0
#include "advee/canopen/sim/drive_sim.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "advee/canopen/device_description.hpp"
#include "advee/canopen/emcy.hpp"
#include "advee/canopen/pdo.hpp"

namespace advee::canopen::sim {

using cia402::Command;
using cia402::State;
namespace cw = cia402::cw;
namespace sw = cia402::sw;

namespace {
constexpr std::uint8_t kMaxMapped = 8;

PdoMapping mapping_from(const ObjectDictionary& od, PdoKind kind, unsigned n) {
  PdoMapping m;
  m.kind = kind;
  m.number = n;
  m.cob_id = od.get<std::uint32_t>(pdo_comm_index(kind, n), 1);
  m.transmission_type = od.get<std::uint8_t>(pdo_comm_index(kind, n), 2);
  const auto count = od.get<std::uint8_t>(pdo_map_index(kind, n), 0);
  for (std::uint8_t s = 1; s <= count && s <= kMaxMapped; ++s)
    m.entries.push_back(PdoEntry::from_raw(od.get<std::uint32_t>(pdo_map_index(kind, n), s)));
  return m;
}
}  // namespace

SimulatedDrive::SimulatedDrive(DriveSimConfig cfg, FrameSender send, NowFn now)
    : cfg_(cfg), send_(std::move(send)), now_(std::move(now)), sdo_(cfg.node, od_, send_, now_) {
  build_dictionary();
  defaults_ = od_;
  install_validators();
  last_step_ = now_();
}

void SimulatedDrive::build_dictionary() {
  // The EDS is the one description of the drive: the master reads the same
  // file to check the identity and to configure the drive.
  DescriptionResult r = cfg_.eds_file.empty()
                            ? parse_device_description(shipped_eds(cfg_.profile), shipped_eds_name(cfg_.profile), cfg_.node)
                            : load_device_description(cfg_.eds_file, cfg_.node);
  if (!r.description) {
    std::string msg = "simulated drive: bad device description";
    for (const auto& e : r.errors) msg += "\n" + e.text();
    throw std::runtime_error(msg);
  }
  od_ = std::move(r.description->od);
  // Per simulated instance (where homing puts the position, which serial
  // number tells it from others of its type for LSS), not per device type.
  od_.set<std::int32_t>(0x607C, 0, cfg_.home_offset);
  if (cfg_.serial) od_.set<std::uint32_t>(0x1018, 4, cfg_.serial);
}

void SimulatedDrive::install_validators() {
  for (unsigned n = 1; n <= 4; ++n) {
    for (PdoKind kind : {PdoKind::kRpdo, PdoKind::kTpdo}) {
      const std::uint16_t comm = pdo_comm_index(kind, n);
      const std::uint16_t map = pdo_map_index(kind, n);
      if (kind == PdoKind::kTpdo) {
        od_.on_write(comm, [this](std::uint8_t) { tpdo_cache_valid_ = false; });
        od_.on_write(map, [this](std::uint8_t) { tpdo_cache_valid_ = false; });
      }
      od_.set_validator(comm, [this, comm](std::uint8_t sub, std::span<const std::uint8_t> d) {
        if (sub != 1) return SdoAbort::kNone;
        const auto cur = od_.get<std::uint32_t>(comm, 1);
        const auto next = load_le<std::uint32_t>(d);
        // CiA 301: the CAN-ID of a valid PDO cannot change without invalidating it first.
        if (!(cur & kPdoCobInvalid) && !(next & kPdoCobInvalid) && (cur & 0x7FF) != (next & 0x7FF))
          return SdoAbort::kInvalidValue;
        return SdoAbort::kNone;
      });
      od_.set_validator(map, [this, kind, comm, map](std::uint8_t sub, std::span<const std::uint8_t> d) {
        if (!(od_.get<std::uint32_t>(comm, 1) & kPdoCobInvalid)) return SdoAbort::kUnsupportedAccess;
        if (sub == 0) {
          const std::uint8_t count = d[0];
          if (count > kMaxMapped) return SdoAbort::kValueTooHigh;
          unsigned bits = 0;
          for (std::uint8_t s = 1; s <= count; ++s) {
            const PdoEntry e = PdoEntry::from_raw(od_.get<std::uint32_t>(map, s));
            const OdEntry* obj = od_.find(e.index, e.sub);
            if (!obj || !obj->mappable || e.bits != obj->value.size() * 8) return SdoAbort::kNotMappable;
            if (kind == PdoKind::kRpdo && obj->access == Access::kReadOnly) return SdoAbort::kNotMappable;
            bits += e.bits;
          }
          return bits > 64 ? SdoAbort::kPdoTooLong : SdoAbort::kNone;
        }
        // Entries change only while the mapping is disabled (sub0 = 0).
        if (od_.get<std::uint8_t>(map, 0) != 0) return SdoAbort::kUnsupportedAccess;
        const PdoEntry e = PdoEntry::from_raw(load_le<std::uint32_t>(d));
        const OdEntry* obj = od_.find(e.index, e.sub);
        if (!obj || !obj->mappable) return SdoAbort::kNotMappable;
        return SdoAbort::kNone;
      });
    }
  }
  od_.on_write(0x6040, [this](std::uint8_t) { process_controlword(); });
  od_.set_validator(0x6060, [this](std::uint8_t, std::span<const std::uint8_t> d) {
    const auto m = static_cast<std::int8_t>(d[0]);
    if (m <= 0 || m > 31 || !(od_.get<std::uint32_t>(0x6502) & (1u << (m - 1)))) return SdoAbort::kInvalidValue;
    return SdoAbort::kNone;
  });
  od_.on_write(0x6060, [this](std::uint8_t) {
    if (faults_.ignore_mode_change) return;
    if (faults_.refuse_mode_change_while_halt && (od_.get<std::uint16_t>(0x6040) & cw::kHalt)) return;
    od_.set<std::int8_t>(0x6061, 0, od_.get<std::int8_t>(0x6060));
    homing_active_ = false;
    moving_ = false;
    update_statusword();
  });
  od_.on_write(0x1017, [this](std::uint8_t) { next_heartbeat_ = now_(); });
  od_.on_write(0x1016, [this](std::uint8_t) {
    master_hb_seen_.reset();
    master_hb_lost_ = false;
  });
}

void SimulatedDrive::power_on() {
  reset(true);
}

void SimulatedDrive::reset(bool application) {
  od_.restore(defaults_, 0x1000, 0x1FFF);
  if (application) {
    od_.restore(defaults_, 0x2000, 0xFFFF);
    pos_ = vel_ = 0;
    moving_ = homing_active_ = homing_attained_ = homing_error_ = setpoint_ack_ = false;
    prev_cw_ = 0;
    state_ = State::kNotReadyToSwitchOn;
  }
  sdo_.reset();
  tpdo_ = {};
  tpdo_cache_valid_ = false;
  rpdo_latched_ = {};
  master_hb_seen_.reset();
  master_hb_lost_ = false;
  guard_toggle_ = false;
  nmt_ = NmtState::kBootUp;
  send_(heartbeat_frame(cfg_.node, NmtState::kBootUp));
  enter_nmt(NmtState::kPreOperational);
  // Transitions 0 and 1 happen on their own after initialisation.
  if (state_ == State::kNotReadyToSwitchOn) set_state(State::kSwitchOnDisabled);
  last_step_ = now_();
}

void SimulatedDrive::enter_nmt(NmtState s) {
  nmt_ = s;
  next_heartbeat_ = now_() + std::chrono::milliseconds(od_.get<std::uint16_t>(0x1017));
  if (s == NmtState::kOperational) tpdo_ = {};  // every TPDO is sent once on start
}

void SimulatedDrive::handle(const CanFrame& f) {
  if (f.id == cob::kNmt) return on_nmt(f);
  if (f.rtr && f.id == cob::kNmtErrorControl + cfg_.node) {
    // Node guarding: state plus a toggle bit that alternates from 0.
    if (faults_.heartbeat_silent) return;  // a silent node answers nothing
    send_(make_frame(f.id, {static_cast<std::uint8_t>(static_cast<std::uint8_t>(nmt_) | (guard_toggle_ ? 0x80 : 0))}));
    guard_toggle_ = !guard_toggle_;
    return;
  }
  if (nmt_ == NmtState::kStopped) {
    if (f.id == cob::kNmtErrorControl + ((od_.get<std::uint32_t>(0x1016, 1) >> 16) & 0x7F)) on_master_heartbeat();
    return;
  }
  if (sdo_.handle(f)) {
    service_tpdos(false);
    return;
  }
  if (f.id == cob::kSync) return on_sync(f);
  const auto master_node = (od_.get<std::uint32_t>(0x1016, 1) >> 16) & 0x7F;
  if (master_node && f.id == cob::kNmtErrorControl + master_node && !f.rtr) return on_master_heartbeat();
  if (nmt_ == NmtState::kOperational && on_rpdo(f)) service_tpdos(false);
}

void SimulatedDrive::on_nmt(const CanFrame& f) {
  if (f.len != 2 || (f.data[1] != 0 && f.data[1] != cfg_.node)) return;
  switch (static_cast<NmtCommand>(f.data[0])) {
    case NmtCommand::kStart: enter_nmt(NmtState::kOperational); service_tpdos(false); break;
    case NmtCommand::kStop: enter_nmt(NmtState::kStopped); break;
    case NmtCommand::kEnterPreOperational: enter_nmt(NmtState::kPreOperational); break;
    case NmtCommand::kResetNode: reset(true); break;
    case NmtCommand::kResetCommunication: reset(false); break;
  }
}

void SimulatedDrive::on_master_heartbeat() {
  master_hb_seen_ = now_();
  master_hb_lost_ = false;
}

void SimulatedDrive::check_master_heartbeat(TimePoint now) {
  const auto entry = od_.get<std::uint32_t>(0x1016, 1);
  const auto ms = entry & 0xFFFF;
  if (!ms || !((entry >> 16) & 0x7F) || !master_hb_seen_ || master_hb_lost_) return;
  if (now - *master_hb_seen_ < std::chrono::milliseconds(ms)) return;
  master_hb_lost_ = true;
  send_emcy(0x8130, 0x11);
  // 0x6007 abort connection option code: 1 fault, 2 disable voltage, 3 quick stop.
  switch (od_.get<std::int16_t>(0x6007)) {
    case 1: inject_fault(0x8130); break;
    case 2: if (state_ != State::kFault) set_state(State::kSwitchOnDisabled); break;
    case 3: if (state_ == State::kOperationEnabled) set_state(State::kQuickStopActive); break;
    default: break;
  }
}

void SimulatedDrive::on_sync(const CanFrame& f) {
  for (unsigned n = 0; n < 4; ++n)
    if (rpdo_latched_[n]) {
      apply_rpdo(n + 1, *rpdo_latched_[n]);
      rpdo_latched_[n].reset();
    }
  if (nmt_ == NmtState::kOperational) service_tpdos(true, f.len ? f.data[0] : 0);
}

bool SimulatedDrive::on_rpdo(const CanFrame& f) {
  for (unsigned n = 1; n <= 4; ++n) {
    const auto cob = od_.get<std::uint32_t>(pdo_comm_index(PdoKind::kRpdo, n), 1);
    if ((cob & kPdoCobInvalid) || (cob & 0x7FF) != f.id || f.rtr) continue;
    ++rpdos_received_;
    if (od_.get<std::uint8_t>(pdo_comm_index(PdoKind::kRpdo, n), 2) <= 240)
      rpdo_latched_[n - 1] = f;
    else
      apply_rpdo(n, f);
    return true;
  }
  return false;
}

void SimulatedDrive::apply_rpdo(unsigned n, const CanFrame& f) {
  const PdoMapping m = mapping_from(od_, PdoKind::kRpdo, n);
  auto codec = PdoCodec::build(m);
  if (!codec) return;
  if (f.len < codec->length()) {
    send_emcy(0x8210, 0x11);  // PDO not processed due to length error
    return;
  }
  bool cw_written = false;
  for (const PdoEntry& e : m.entries) {
    od_.set_raw(e.index, e.sub, codec->get_unsigned(f, e.index, e.sub).value_or(0));
    if (e.index == 0x6040) cw_written = true;
  }
  if (cw_written) process_controlword();
}

void SimulatedDrive::set_state(State s) {
  state_ = s;
  if (s != State::kOperationEnabled) {
    moving_ = false;
    homing_active_ = false;
  }
  update_statusword();
}

void SimulatedDrive::process_controlword() {
  const auto w = od_.get<std::uint16_t>(0x6040);
  const auto prev = prev_cw_;
  prev_cw_ = w;
  if (auto cmd = cia402::command_in(w, prev, state_)) {
    switch (state_) {
      case State::kSwitchOnDisabled:
        if (*cmd == Command::kShutdown) set_state(State::kReadyToSwitchOn);
        break;
      case State::kReadyToSwitchOn:
        if (*cmd == Command::kSwitchOn) set_state(State::kSwitchedOn);
        if (*cmd == Command::kEnableOperation) set_state(State::kOperationEnabled);  // 3 + 4
        if (*cmd == Command::kDisableVoltage || *cmd == Command::kQuickStop) set_state(State::kSwitchOnDisabled);
        break;
      case State::kSwitchedOn:
        if (*cmd == Command::kEnableOperation) set_state(State::kOperationEnabled);
        if (*cmd == Command::kShutdown) set_state(State::kReadyToSwitchOn);
        if (*cmd == Command::kDisableVoltage || *cmd == Command::kQuickStop) set_state(State::kSwitchOnDisabled);
        break;
      case State::kOperationEnabled:
        if (*cmd == Command::kDisableOperation) set_state(State::kSwitchedOn);
        if (*cmd == Command::kShutdown) set_state(State::kReadyToSwitchOn);
        if (*cmd == Command::kDisableVoltage) set_state(State::kSwitchOnDisabled);
        if (*cmd == Command::kQuickStop) set_state(State::kQuickStopActive);
        break;
      case State::kQuickStopActive:
        if (*cmd == Command::kDisableVoltage) set_state(State::kSwitchOnDisabled);
        if (*cmd == Command::kEnableOperation && !faults_.refuse_transition_16) set_state(State::kOperationEnabled);
        break;
      case State::kFault:
        if (*cmd == Command::kFaultReset) {
          od_.set<std::uint16_t>(0x603F, 0, 0);
          od_.set<std::uint8_t>(0x1001, 0, 0);
          send_emcy(0x0000, 0);
          set_state(State::kSwitchOnDisabled);
        }
        break;
      default:
        break;
    }
  }
  // Mode-specific edges of bit 4 while enabled.
  const bool rise = (w & cw::kNewSetPoint) && !(prev & cw::kNewSetPoint);
  const bool fall = !(w & cw::kNewSetPoint) && (prev & cw::kNewSetPoint);
  if (state_ == State::kOperationEnabled && rise) {
    if (mode() == static_cast<std::int8_t>(cia402::Mode::kProfilePosition)) {
      const double t = od_.get<std::int32_t>(0x607A);
      target_pos_ = (w & cw::kRelative) ? target_pos_ + t : t;
      moving_ = true;
      setpoint_ack_ = true;
    } else if (mode() == static_cast<std::int8_t>(cia402::Mode::kHoming)) {
      homing_active_ = true;
      homing_attained_ = false;
      homing_error_ = false;
      homing_start_ = pos_;
      homing_start_travel_ = travel_;
    }
  }
  if (fall) setpoint_ack_ = false;
  update_statusword();
}

void SimulatedDrive::update_statusword() {
  std::uint16_t s = cia402::statusword_bits(state_) | sw::kRemote;
  const auto m = mode();
  const auto w = od_.get<std::uint16_t>(0x6040);
  const bool halted = (w & cw::kHalt) != 0;
  if (m == static_cast<std::int8_t>(cia402::Mode::kProfileVelocity)) {
    const double target = halted ? 0 : od_.get<std::int32_t>(0x60FF);
    if (std::fabs(vel_ - target) < 1.0) s |= sw::kTargetReached;
    if (vel_ == 0) s |= sw::kSpeedZero;
  } else if (m == static_cast<std::int8_t>(cia402::Mode::kProfilePosition)) {
    if (!moving_) s |= sw::kTargetReached;
    if (setpoint_ack_) s |= sw::kSetPointAcknowledge;
  } else if (m == static_cast<std::int8_t>(cia402::Mode::kHoming)) {
    if (!homing_active_) s |= sw::kTargetReached;
    if (homing_attained_) s |= sw::kHomingAttained;
    if (homing_error_) s |= sw::kHomingError;
  }
  od_.set<std::uint16_t>(0x6041, 0, s);
}

void SimulatedDrive::step(double dt) {
  const auto w = od_.get<std::uint16_t>(0x6040);
  const bool halted = (w & cw::kHalt) != 0;
  double target = 0;
  double accel = od_.get<std::uint32_t>(0x6083);
  const double decel = od_.get<std::uint32_t>(0x6084);
  switch (state_) {
    case State::kQuickStopActive:
    case State::kFaultReactionActive:
      target = 0;
      accel = od_.get<std::uint32_t>(0x6085);
      break;
    case State::kOperationEnabled:
      if (halted) {
        accel = decel;
      } else if (mode() == static_cast<std::int8_t>(cia402::Mode::kProfileVelocity)) {
        target = od_.get<std::int32_t>(0x60FF);
        if (std::fabs(target) < std::fabs(vel_)) accel = decel;
      } else if (mode() == static_cast<std::int8_t>(cia402::Mode::kProfilePosition) && moving_) {
        const double dist = target_pos_ - pos_;
        const double vmax = od_.get<std::uint32_t>(0x6081);
        // Speed from which the deceleration ramp still stops at the target.
        const double vstop = std::sqrt(2.0 * decel * std::fabs(dist) / cfg_.position_per_velocity);
        target = std::copysign(std::min(vmax, vstop), dist);
        if (std::fabs(dist) < 0.5) {
          travel_ += target_pos_ - pos_;
          pos_ = target_pos_;
          vel_ = target = 0;
          moving_ = false;
        }
      } else if (mode() == static_cast<std::int8_t>(cia402::Mode::kHoming) && homing_active_) {
        const auto method = od_.get<std::int8_t>(0x6098);
        if (method == 35 || method == 37) {  // current position is home
          pos_ = od_.get<std::int32_t>(0x607C);
          homing_active_ = false;
          homing_attained_ = true;
          break;
        }
        // The switch and the search in the counter's frame, or in the mechanism's.
        const bool mech = cfg_.home_switch_travel.has_value();
        const double sw_at = mech ? *cfg_.home_switch_travel : cfg_.home_switch_position;
        const double here = mech ? travel_ : pos_, start = mech ? homing_start_travel_ : homing_start_;
        const double dir = sw_at >= start ? 1.0 : -1.0;
        target = dir * od_.get<std::uint32_t>(0x6099, 1);
        accel = od_.get<std::uint32_t>(0x609A);
        const bool at_switch = dir > 0 ? here >= sw_at : here <= sw_at;
        if (at_switch && !faults_.homing_switch_missing && method != 0) {
          // A mechanical switch latches the counter at its edge: the part of
          // the last step past it stays in the position.
          pos_ = od_.get<std::int32_t>(0x607C) + (mech ? here - sw_at : 0.0);
          vel_ = target = 0;
          homing_active_ = false;
          homing_attained_ = true;
        } else if (std::fabs(here - start) > 100000 || method == 0) {
          vel_ = target = 0;
          homing_active_ = false;
          homing_error_ = true;
        }
      }
      break;
    default:
      vel_ = 0;  // power stage off: the motor coasts; the model stops it at once
      break;
  }
  const double dv = accel * dt;
  if (accel <= 0 || std::fabs(target - vel_) <= dv)
    vel_ = target;
  else
    vel_ += target > vel_ ? dv : -dv;
  pos_ += vel_ * cfg_.position_per_velocity * dt;
  travel_ += vel_ * cfg_.position_per_velocity * dt;

  if (state_ == State::kQuickStopActive && vel_ == 0) {
    const bool has_option = od_.find(0x605A, 0) != nullptr;
    const auto option = has_option ? od_.get<std::int16_t>(0x605A) : 6;
    if (option >= 0 && option <= 4) set_state(State::kSwitchOnDisabled);
  }
  if (state_ == State::kFaultReactionActive && vel_ == 0) set_state(State::kFault);
  od_.set<std::int32_t>(0x6064, 0, static_cast<std::int32_t>(std::lround(pos_)));
  od_.set<std::int32_t>(0x606C, 0, static_cast<std::int32_t>(std::lround(vel_)));
  update_statusword();
}

void SimulatedDrive::refresh_tpdo_cache() {
  for (unsigned n = 1; n <= 4; ++n) {
    TpdoCache& c = tpdo_cache_[n - 1];
    c.mapping = mapping_from(od_, PdoKind::kTpdo, n);
    c.codec = c.mapping.entries.empty() ? std::nullopt : PdoCodec::build(c.mapping);
    c.inhibit_100us = od_.get<std::uint16_t>(pdo_comm_index(PdoKind::kTpdo, n), 3);
    c.event_timer_ms = od_.get<std::uint16_t>(pdo_comm_index(PdoKind::kTpdo, n), 5);
  }
  tpdo_cache_valid_ = true;
}

void SimulatedDrive::service_tpdos(bool sync, std::uint8_t) {
  tpdo_due_.reset();
  if (nmt_ != NmtState::kOperational) return;
  if (!tpdo_cache_valid_) refresh_tpdo_cache();
  const TimePoint now = now_();
  auto due_at = [this](TimePoint t) {
    if (!tpdo_due_ || t < *tpdo_due_) tpdo_due_ = t;
  };
  for (unsigned n = 1; n <= 4; ++n) {
    const TpdoCache& c = tpdo_cache_[n - 1];
    if (!c.codec) continue;
    CanFrame f = c.codec->blank();
    for (const PdoEntry& e : c.mapping.entries) {
      const OdEntry* obj = od_.find(e.index, e.sub);
      c.codec->set(f, e.index, e.sub, obj ? load_le<std::uint64_t>(obj->value) : 0);
    }
    TpdoState& st = tpdo_[n - 1];
    const std::uint8_t type = c.mapping.transmission_type;
    bool due = false;
    if (type >= 1 && type <= 240) {
      if (sync && ++st.sync_count >= type) {
        st.sync_count = 0;
        due = true;
      }
    } else if (type == 0) {
      due = sync && (!st.last || !(*st.last == f));
    } else if (type >= 254) {
      const auto inhibit = std::chrono::microseconds(100 * c.inhibit_100us);
      const auto timer = std::chrono::milliseconds(c.event_timer_ms);
      const bool changed = !st.last || !(*st.last == f);
      const bool timer_due = timer.count() > 0 && now - st.last_sent >= timer;
      const bool inhibited = st.last && now - st.last_sent < inhibit;
      due = (changed || timer_due) && !inhibited;
      if (changed && inhibited) due_at(st.last_sent + inhibit);
      if (timer.count() > 0) due_at((due ? now : st.last_sent) + timer);
    }
    if (!due) continue;
    st.last = f;
    st.last_sent = now;
    ++tpdos_sent_;
    send_(f);
  }
}

void SimulatedDrive::send_emcy(std::uint16_t code, std::uint8_t reg) {
  Emcy e;
  e.node = cfg_.node;
  e.code = code;
  e.error_register = reg;
  send_(emcy_frame(e));
}

void SimulatedDrive::inject_fault(std::uint16_t code) {
  od_.set<std::uint16_t>(0x603F, 0, code);
  od_.set<std::uint8_t>(0x1001, 0, 0x01);
  send_emcy(code, 0x01);
  set_state(vel_ != 0 ? State::kFaultReactionActive : State::kFault);
  service_tpdos(false);
}

bool SimulatedDrive::dynamic() const {
  return vel_ != 0 || moving_ || homing_active_ || state_ == State::kQuickStopActive ||
         state_ == State::kFaultReactionActive ||
         (state_ == State::kOperationEnabled && mode() == static_cast<std::int8_t>(cia402::Mode::kProfileVelocity) &&
          od_.get<std::int32_t>(0x60FF) != 0 && !(od_.get<std::uint16_t>(0x6040) & cw::kHalt));
}

void SimulatedDrive::poll() {
  const TimePoint now = now_();
  sdo_.poll();
  if (!dynamic()) {
    // Nothing moves: no need to integrate the idle time step by step.
    last_step_ = now;
  }
  while (now - last_step_ >= cfg_.step) {
    last_step_ += cfg_.step;
    step(std::chrono::duration<double>(cfg_.step).count());
  }
  check_master_heartbeat(now);
  const auto period = od_.get<std::uint16_t>(0x1017);
  if (period && now >= next_heartbeat_) {
    if (!faults_.heartbeat_silent) send_(heartbeat_frame(cfg_.node, nmt_));
    next_heartbeat_ += std::chrono::milliseconds(period);
    if (next_heartbeat_ <= now) next_heartbeat_ = now + std::chrono::milliseconds(period);
  }
  service_tpdos(false);
}

std::optional<TimePoint> SimulatedDrive::deadline() const {
  // Stepping at full rate only while something moves keeps an idle simulator
  // (and the VM running it) quiet.
  TimePoint d = dynamic() ? last_step_ + cfg_.step : now_() + std::chrono::milliseconds(50);
  auto take = [&d](std::optional<TimePoint> t) {
    if (t && *t < d) d = *t;
  };
  take(sdo_.deadline());
  take(tpdo_due_);
  if (od_.get<std::uint16_t>(0x1017)) take(next_heartbeat_);
  const auto entry = od_.get<std::uint32_t>(0x1016, 1);
  if ((entry & 0xFFFF) && master_hb_seen_ && !master_hb_lost_) take(*master_hb_seen_ + std::chrono::milliseconds(entry & 0xFFFF));
  return d;
}

}  // namespace advee::canopen::sim
