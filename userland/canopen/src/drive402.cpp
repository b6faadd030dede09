// SPDX-License-Identifier: GPL-2.0
#include "advee/canopen/drive402.hpp"

#include <cstdio>
#include <memory>

#include "advee/canopen/pdo_config.hpp"
#include "advee/canopen/sdo_sequence.hpp"

namespace advee::canopen {

using cia402::State;
namespace cw = cia402::cw;
namespace sw = cia402::sw;

namespace {
constexpr auto kModePollInterval = std::chrono::milliseconds(5);

std::string describe_need(PdoKind kind, unsigned n, const std::vector<PdoEntry>& need) {
  PdoMapping m;
  m.kind = kind;
  m.number = n;
  m.entries = need;
  m.cob_id = 0;
  std::string s = to_string(m);
  return s.substr(s.find(':') + 1);
}
}  // namespace

void take_pdos_from_device(DriveConfig& d, std::initializer_list<std::uint16_t> control,
                           std::initializer_list<std::uint16_t> status) {
  if (!d.device) return;
  if (const PdoMapping* m = find_pdo(d.device->pdos, PdoKind::kRpdo, control)) {
    d.control_rpdo = m->number;
    d.control_entries = m->entries;
  }
  if (const PdoMapping* m = find_pdo(d.device->pdos, PdoKind::kTpdo, status)) {
    d.status_tpdo = m->number;
    d.status_entries = m->entries;
  }
}

Drive402::Drive402(Master& master, DriveConfig cfg)
    : master_(master),
      cfg_(std::move(cfg)),
      axis_(cfg_.axis, [&master] { return master.now(); }, [this](std::uint16_t) { send_control(); }) {
  service_ = master_.attach(*this);
  master_.sdo(cfg_.node).set_timeout(cfg_.sdo_timeout);
  emcy_listener_ = master_.add_emcy_listener([this](const Emcy& e) {
    if (e.node != cfg_.node) return;
    emit({DriveEventKind::kEmcy, cfg_.node, e.code, to_string(e)});
  });
  hb_listener_ = master_.add_heartbeat_listener([this](const HeartbeatUpdate& u) {
    if (u.node != cfg_.node) return;
    if (u.event == HeartbeatEvent::kLost) emit({DriveEventKind::kHeartbeatLost, cfg_.node, 0, cfg_.name + ": heartbeat lost"});
    if (u.event == HeartbeatEvent::kResumed) emit({DriveEventKind::kHeartbeatResumed, cfg_.node, 0, cfg_.name + ": heartbeat resumed"});
    if (u.event != HeartbeatEvent::kBootUp) return;
    if (booted_) {
      // Its PDO configuration and heartbeat setup are gone: it must boot again.
      booted_ = false;
      emit({DriveEventKind::kRebooted, cfg_.node, 0, cfg_.name + ": drive rebooted"});
    } else if (booting_) {
      // Whatever this boot wrote so far is gone: it fails, its pending
      // answers are dropped, and the owner boots again.
      boot_lifetime_.renew();
      device_boot_.reset();  // its transfers' answers are dropped too
      boot_failed("drive rebooted during boot", make_error_code(AxisError::kCancelled));
    }
  });
}

void Drive402::emit(DriveEvent e) {
  for (auto& cb : listeners_) cb(e);
}

void Drive402::boot_failed(const std::string& why, std::error_code ec) {
  char head[64];
  std::snprintf(head, sizeof head, "%s (node %u): boot failed: ", cfg_.name.c_str(), cfg_.node);
  boot_error_ = head + why + ": " + ec.message() + (mismatch_.empty() ? "" : " (" + mismatch_ + ")");
  booting_ = false;
  auto done = std::move(boot_done_);
  boot_done_ = nullptr;
  if (done) done(ec);
}

void Drive402::configure_pdo(PdoKind kind, unsigned number, const std::vector<PdoEntry>& need,
                             std::function<void(std::error_code, const PdoMapping&)> done) {
  SdoClient& sdo = master_.sdo(cfg_.node);
  read_pdo_mapping(sdo, kind, number, boot_lifetime_.wrap([this, kind, number, need, done, &sdo](std::error_code ec, const PdoMapping& m) {
    if (ec) return done(ec, m);
    PdoMapping wanted = m;
    if (m.entries != need) {
      if (!cfg_.remap_if_different) {
        mismatch_ = "device has " + to_string(m) + ", driver needs" + describe_need(kind, number, need);
        return done(make_error_code(AxisError::kPdoMismatch), m);
      }
      wanted.entries = need;
    } else if (m.enabled()) {
      return done({}, m);  // nothing to write
    }
    // Event-driven and valid on the predefined COB-ID if the device has none.
    if ((wanted.cob_id & 0x7FF) == 0) wanted.cob_id = default_pdo_cob_id(kind, number, cfg_.node);
    wanted.cob_id &= ~kPdoCobInvalid;
    wanted.transmission_type = 255;
    std::vector<SdoWrite> writes = m.entries != need ? pdo_remap_writes(wanted)
                                                     : std::vector<SdoWrite>{pdo_enable_write(wanted, true)};
    run_sdo_writes(sdo, std::move(writes),
                   boot_lifetime_.wrap([done, wanted](const SdoSequenceResult& r) { done(r.error, wanted); }));
  }));
}

void Drive402::boot(Done done) {
  boot_done_ = std::move(done);
  boot_error_.clear();
  mismatch_.clear();
  booted_ = false;
  booting_ = true;
  boot_lifetime_.renew();  // answers of an earlier boot are not this one's
  status_sub_.reset();
  if (!cfg_.device) return boot_driver();
  NodeBootConfig device = *cfg_.device;
  device.node = cfg_.node;
  device.name = cfg_.name;
  device.start = false;  // the drive starts once its PDOs are checked below
  device_boot_ = std::make_unique<NodeBoot>(master_, std::move(device));
  device_boot_->boot(boot_lifetime_.wrap([this](std::error_code ec, const std::string&) {
    if (ec) return boot_failed(device_boot_->reason(), ec);
    boot_driver();
  }));
}

void Drive402::boot_driver() {
  SdoClient& sdo = master_.sdo(cfg_.node);
  master_.nmt(NmtCommand::kEnterPreOperational, cfg_.node);
  std::vector<SdoWrite> hb;
  hb.push_back(SdoWrite::of<std::uint16_t>(0x1017, 0, cfg_.heartbeat_ms));
  if (cfg_.master_heartbeat_timeout_ms && master_.heartbeat_period().count() > 0)
    hb.push_back(SdoWrite::of<std::uint32_t>(
        0x1016, 1, (static_cast<std::uint32_t>(master_.config().node_id) << 16) | cfg_.master_heartbeat_timeout_ms));
  run_sdo_writes(sdo, std::move(hb), boot_lifetime_.wrap([this](const SdoSequenceResult& r) {
    if (r.error) return boot_failed("heartbeat configuration", r.error);
    master_.heartbeat_consumer().monitor(cfg_.node, std::chrono::milliseconds(cfg_.heartbeat_ms) * cfg_.heartbeat_tolerance);
    configure_pdo(PdoKind::kRpdo, cfg_.control_rpdo, cfg_.control_entries, [this](std::error_code ec, const PdoMapping& m) {
      if (ec) return boot_failed("control RPDO", ec);
      control_map_ = m;
      control_codec_ = PdoCodec::build(m);
      if (!control_codec_) return boot_failed("control RPDO codec", make_error_code(AxisError::kPdoMismatch));
      control_frame_ = control_codec_->blank();
      configure_pdo(PdoKind::kTpdo, cfg_.status_tpdo, cfg_.status_entries, [this](std::error_code ec2, const PdoMapping& t) {
        if (ec2) return boot_failed("status TPDO", ec2);
        status_map_ = t;
        status_codec_ = PdoCodec::build(t);
        if (!status_codec_) return boot_failed("status TPDO codec", make_error_code(AxisError::kPdoMismatch));
        status_sub_ = master_.subscribe(status_codec_->can_id(), [this](const CanFrame& f) { on_status(f); });
        // Reading the mode display once tells set_mode() where we start.
        master_.sdo(cfg_.node).read<std::int8_t>(0x6061, 0, boot_lifetime_.wrap([this](std::error_code ec3, std::int8_t m) {
          if (ec3) return boot_failed("modes of operation display", ec3);
          mode_ = static_cast<cia402::Mode>(m);
          master_.nmt(NmtCommand::kStart, cfg_.node);
          booted_ = true;
          booting_ = false;
          auto d = std::move(boot_done_);
          boot_done_ = nullptr;
          if (d) d({});
        }));
      });
    });
  }));
}

void Drive402::send_control() {
  if (!control_codec_) return;
  control_codec_->set(control_frame_, 0x6040, 0, axis_.controlword());
  master_.send(control_frame_);
}

bool Drive402::set_target(std::uint16_t index, std::uint8_t sub, std::int64_t value) {
  if (!control_codec_ || !control_codec_->set(control_frame_, index, sub, static_cast<std::uint64_t>(value)))
    return false;
  send_control();
  return true;
}

void Drive402::on_status(const CanFrame& f) {
  auto word = status_codec_->get_unsigned(f, 0x6041, 0);
  if (!word) return;
  ++status_frames_;
  last_status_ = f;
  const State before = axis_.state();
  const bool had = axis_.has_statusword();
  axis_.on_statusword(static_cast<std::uint16_t>(*word));
  if (had && before != State::kFault && axis_.state() == State::kFault)
    emit({DriveEventKind::kFault, cfg_.node, 0, cfg_.name + ": drive entered fault"});
  const std::uint16_t s = axis_.statusword();
  switch (motion_) {
    case Motion::kSetPoint:
      if (s & sw::kSetPointAcknowledge) {
        axis_.set_bits(cw::kNewSetPoint, 0);
        motion_ = Motion::kMoving;
        motion_deadline_ = master_.now() + cfg_.move_timeout;
      }
      break;
    case Motion::kMoving:
      if ((s & sw::kTargetReached) && !(s & sw::kSetPointAcknowledge)) finish_motion({});
      break;
    case Motion::kHoming:
      if (s & sw::kHomingError) {
        axis_.set_bits(cw::kHomingStart, 0);
        finish_motion(make_error_code(AxisError::kHomingError));
      } else if ((s & sw::kHomingAttained) && (s & sw::kTargetReached)) {
        axis_.set_bits(cw::kHomingStart, 0);
        finish_motion({});
      }
      break;
    default:
      break;
  }
  if (motion_ != Motion::kNone && motion_ != Motion::kModeWait && axis_.state() != State::kOperationEnabled)
    finish_motion(make_error_code(AxisError::kNotReady));
}

std::optional<std::int64_t> Drive402::feedback(std::uint16_t index, std::uint8_t sub) const {
  if (!last_status_ || !status_codec_) return std::nullopt;
  return status_codec_->get_signed(*last_status_, index, sub);
}

void Drive402::finish_motion(std::error_code ec) {
  motion_ = Motion::kNone;
  next_mode_read_.reset();
  auto done = std::move(motion_done_);
  motion_done_ = nullptr;
  if (done) done(ec);
}

void Drive402::set_mode(cia402::Mode mode, Done done) {
  if (motion_ != Motion::kNone) finish_motion(make_error_code(AxisError::kCancelled));
  motion_done_ = std::move(done);
  motion_ = Motion::kModeWait;
  wanted_mode_ = mode;
  motion_deadline_ = master_.now() + cfg_.mode_timeout;
  // Some drives ignore a mode change while halt is set (ros2_canopen #234).
  axis_.set_bits(cw::kHalt | cw::kNewSetPoint, 0);
  master_.sdo(cfg_.node).write<std::int8_t>(0x6060, 0, static_cast<std::int8_t>(mode),
                                            lifetime_.wrap([this](const SdoResult& r) {
                                              if (motion_ != Motion::kModeWait) return;
                                              if (!r.ok()) return finish_motion(r.error());
                                              read_mode_display();
                                            }));
}

void Drive402::read_mode_display() {
  mode_read_pending_ = true;
  master_.sdo(cfg_.node).read<std::int8_t>(0x6061, 0, lifetime_.wrap([this](std::error_code ec, std::int8_t m) {
    mode_read_pending_ = false;
    if (motion_ != Motion::kModeWait) return;
    if (ec) return finish_motion(ec);
    if (m == static_cast<std::int8_t>(wanted_mode_)) {
      mode_ = wanted_mode_;
      return finish_motion({});
    }
    next_mode_read_ = master_.now() + kModePollInterval;
  }));
}

void Drive402::move_to(std::int32_t position, bool relative, Done done) {
  if (axis_.state() != State::kOperationEnabled || mode_ != cia402::Mode::kProfilePosition)
    return done(make_error_code(AxisError::kNotReady));
  if (motion_ != Motion::kNone) finish_motion(make_error_code(AxisError::kCancelled));
  if (!control_codec_->set(control_frame_, 0x607A, 0, static_cast<std::uint32_t>(position)))
    return done(make_error_code(AxisError::kPdoMismatch));
  motion_done_ = std::move(done);
  motion_ = Motion::kSetPoint;
  motion_deadline_ = master_.now() + cfg_.setpoint_timeout;
  axis_.set_bits(cw::kNewSetPoint | cw::kChangeImmediately | cw::kRelative | cw::kHalt,
                 cw::kNewSetPoint | cw::kChangeImmediately | (relative ? cw::kRelative : 0));
}

void Drive402::home(Done done) {
  if (axis_.state() != State::kOperationEnabled || mode_ != cia402::Mode::kHoming)
    return done(make_error_code(AxisError::kNotReady));
  if (motion_ != Motion::kNone) finish_motion(make_error_code(AxisError::kCancelled));
  motion_done_ = std::move(done);
  motion_ = Motion::kHoming;
  motion_deadline_ = master_.now() + cfg_.homing_timeout;
  axis_.set_bits(cw::kHomingStart | cw::kHalt, 0);  // make sure the next write is a rising edge
  axis_.set_bits(cw::kHomingStart, cw::kHomingStart);
}

void Drive402::poll() {
  axis_.poll();
  if (motion_ == Motion::kNone) return;
  const TimePoint now = master_.now();
  if (motion_ == Motion::kModeWait && next_mode_read_ && now >= *next_mode_read_ && !mode_read_pending_) {
    next_mode_read_.reset();
    read_mode_display();
  }
  if (now >= motion_deadline_) {
    switch (motion_) {
      case Motion::kModeWait: return finish_motion(make_error_code(AxisError::kModeTimeout));
      case Motion::kSetPoint:
        axis_.set_bits(cw::kNewSetPoint, 0);
        return finish_motion(make_error_code(AxisError::kSetPointTimeout));
      case Motion::kMoving: return finish_motion(make_error_code(AxisError::kTransitionTimeout));
      case Motion::kHoming:
        axis_.set_bits(cw::kHomingStart, 0);
        return finish_motion(make_error_code(AxisError::kHomingTimeout));
      default: break;
    }
  }
}

std::optional<TimePoint> Drive402::deadline() const {
  std::optional<TimePoint> d = axis_.deadline();
  auto take = [&d](std::optional<TimePoint> t) {
    if (t && (!d || *t < *d)) d = t;
  };
  if (motion_ != Motion::kNone) take(motion_deadline_);
  take(next_mode_read_);
  return d;
}

}  // namespace advee::canopen
