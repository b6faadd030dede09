// SPDX-License-Identifier: GPL-2.0
#include "advee/driver_canbus/controller.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "advee/canopen/sdo_sequence.hpp"

namespace advee::driver_canbus {

using canopen::AxisError;
using canopen::DriveEvent;
using canopen::DriveEventKind;
using canopen::cia402::State;
using module::ErrorType;
using module::Severity;

namespace {

std::string node_name(const char* what, std::uint8_t node) {
  return std::string(what) + " (node " + std::to_string(node) + ")";
}

std::string fmt(const char* f, double v) {
  char b[32];
  std::snprintf(b, sizeof b, f, v);
  return b;
}

std::string hex4(std::uint32_t v) {
  char b[12];
  std::snprintf(b, sizeof b, "0x%04X", v);
  return b;
}

}  // namespace

DriveController::DriveController(canopen::Master& master, ControllerConfig cfg, Report report_fn)
    : master_(master),
      cfg_(std::move(cfg)),
      report_(std::move(report_fn)),
      epos_(master, cfg_.epos),
      icla_(master, cfg_.icla),
      prop_{Axis::kPropulsion, &epos_.drive(), node_name("epos", cfg_.epos.node)},
      steer_{Axis::kSteering, &icla_.drive(), node_name("icla", cfg_.icla.node)},
      watchdog_(master, cfg_.command_timeout, [this] {
        const bool was = timed_out_;
        timed_out_ = true;
        // Already standing (held, booting, a drive gone): nothing to stop.
        if (was || held() || !ready()) return;
        report(Severity::Warning, ErrorType::Timeout, kErrCommandTimeout,
               "no LL_CMD_MOTION for " +
                   std::to_string(std::chrono::duration_cast<std::chrono::milliseconds>(cfg_.command_timeout).count()) +
                   " ms: propulsion quick stop");
        quick_stop_propulsion("command timeout");
      }) {
  service_ = master_.attach(*this);
  epos_.drive().on_event([this](const DriveEvent& e) { on_drive_event(prop_, e); });
  icla_.drive().on_event([this](const DriveEvent& e) { on_drive_event(steer_, e); });
}

bool DriveController::ready() const { return started_ && prop_.online && steer_.online; }

void DriveController::start(Started done) {
  struct Join {
    int left = 2;
    std::string why;
  };
  auto join = std::make_shared<Join>();
  // CiA 302-2: the NMT master enters operational, then starts its slaves.
  master_.set_nmt_state(canopen::NmtState::kOperational);
  auto one = [this, join, done](bool ok, const std::string& why) {
    if (!ok) join->why += (join->why.empty() ? "" : "; ") + why;
    if (--join->left > 0) return;
    if (!join->why.empty()) return done(false, join->why);
    started_ = true;
    if (!held()) {
      ensure_enabled(prop_);
      ensure_enabled(steer_);
    }
    if (cfg_.home_on_start) home_steering();
    done(true, {});
  };
  boot(prop_, [this, one](bool ok) { one(ok, prop_.drive->boot_error()); });
  boot(steer_, [this, one](bool ok) { one(ok, steer_.drive->boot_error()); });
}

void DriveController::boot(Unit& u, std::function<void(bool)> then) {
  u.booting = true;
  u.online = false;
  u.enabling = false;
  auto done = [this, &u, then](std::error_code ec) {
    u.booting = false;
    if (ec) {
      report(Severity::Error, ErrorType::Device, kErrBoot,
             u.drive->boot_error().empty() ? u.name + ": boot failed: " + ec.message() : u.drive->boot_error());
      if (started_) u.reboot_at = master_.now() + cfg_.retry;
      return then(false);
    }
    u.online = true;
    u.enable_after.reset();
    report(Severity::Notice, ErrorType::Device, kErrBooted,
           u.name + (u.axis == Axis::kPropulsion ? ": booted, profile velocity" : ": booted, profile position"));
    then(true);
  };
  if (u.axis == Axis::kPropulsion) return epos_.boot(done);
  icla_.boot([this, done](std::error_code ec) {
    if (ec) return done(ec);
    canopen::run_sdo_writes(icla_.drive().sdo(),
                            {canopen::SdoWrite::of<std::uint32_t>(0x6083, 0, cfg_.steering_acceleration),
                             canopen::SdoWrite::of<std::uint32_t>(0x6084, 0, cfg_.steering_deceleration)},
                            [done](const canopen::SdoSequenceResult& r) { done(r.error); });
  });
}

void DriveController::update_heartbeat_error() {
  master_.set_error(canopen::kEmcyHeartbeatError, prop_.heartbeat_lost || steer_.heartbeat_lost);
}

void DriveController::on_drive_event(Unit& u, const DriveEvent& e) {
  switch (e.kind) {
    case DriveEventKind::kEmcy:
      u.emcy = e.emcy_code;
      if (e.emcy_code == 0)
        report(Severity::Notice, ErrorType::Device, kErrEmcy, u.name + ": EMCY error reset");
      else
        report(Severity::Error, ErrorType::Device, kErrEmcy, u.name + ": EMCY " + hex4(e.emcy_code) + ": " + e.text);
      return;
    case DriveEventKind::kFault:
      report(Severity::Error, ErrorType::Device, kErrFault,
             u.name + ": drive entered fault; the next motion command resets it");
      u.enable_after.reset();
      if (u.axis == Axis::kSteering) {
        moving_ = false;
        sent_steering_.reset();
        quick_stop_propulsion("steering fault");
      } else {
        pending_speed_.reset();
        cmd_speed_ = 0;
      }
      return;
    case DriveEventKind::kHeartbeatLost:
      if (!u.online) return;
      u.online = false;
      u.heartbeat_lost = true;
      update_heartbeat_error();
      report(Severity::Error, ErrorType::Timeout, kErrHeartbeatLost, u.name + ": heartbeat lost");
      if (u.axis == Axis::kSteering) {
        moving_ = false;
        sent_steering_.reset();
        quick_stop_propulsion("steering offline");
      } else {
        pending_speed_.reset();
        cmd_speed_ = 0;
      }
      return;
    case DriveEventKind::kHeartbeatResumed:
      if (u.booting || !u.drive->booted()) return;
      u.online = true;
      u.heartbeat_lost = false;
      update_heartbeat_error();
      report(Severity::Notice, ErrorType::Timeout, kErrHeartbeatResumed, u.name + ": heartbeat resumed");
      return;
    case DriveEventKind::kRebooted:
      u.online = false;
      u.emcy = 0;
      u.heartbeat_lost = false;  // it is back; a failed boot is reported as such
      update_heartbeat_error();
      report(Severity::Warning, ErrorType::Device, kErrRebooted,
             u.name + ": drive rebooted (boot-up message), booting it again" +
                 (u.axis == Axis::kSteering ? "; the steering must be homed again" : ""));
      if (u.axis == Axis::kSteering) {
        homed_ = false;
        homing_ = false;
        moving_ = false;
        sent_steering_.reset();
        pending_steering_.reset();
        quick_stop_propulsion("steering rebooted");
      } else {
        pending_speed_.reset();
        cmd_speed_ = 0;
      }
      // From poll(), not from inside the master's frame dispatch.
      if (started_) u.reboot_at = master_.now();
      return;
  }
}

void DriveController::ensure_enabled(Unit& u) {
  if (!u.online || u.enabling || held()) return;
  if (u.drive->axis().state() == State::kOperationEnabled) return on_enabled(u);
  if (u.enable_after && master_.now() < *u.enable_after) return;
  u.enabling = true;
  u.drive->enable([this, &u](std::error_code ec) {
    u.enabling = false;
    if (ec == AxisError::kCancelled) return;  // a quick stop came first
    if (ec) {
      u.enable_after = master_.now() + cfg_.retry;
      report(Severity::Error, ErrorType::Device, kErrDrive, u.name + ": enable failed: " + ec.message());
      return;
    }
    u.enable_after.reset();
    on_enabled(u);
  });
}

void DriveController::on_enabled(Unit& u) {
  if (held()) return;
  if (u.axis == Axis::kPropulsion) {
    if (!pending_speed_ || timed_out_) return;
    cmd_speed_ = *pending_speed_;
    pending_speed_.reset();
    epos_.set_speed(cmd_speed_);
    return;
  }
  if (homing_requested_) return start_homing();
  send_pending_steering();
}

void DriveController::motion(double speed, double steering) {
  watchdog_.feed();
  if (!started_ || paused_) return;
  auto refuse = [this](const std::string& why) {
    if (!warned_refused_)
      report(Severity::Warning, ErrorType::Unknown, kErrRefused, "LL_CMD_MOTION refused: " + why);
    warned_refused_ = true;
  };
  if (stop_engaged_) return refuse("LL_EVENT_STOP engaged (until stop=false)");
  if (!prop_.online) return refuse(prop_.name + " offline");
  if (!steer_.online) return refuse(steer_.name + " offline");
  warned_refused_ = false;
  if (!std::isfinite(speed) || !std::isfinite(steering)) return refuse("speed or steering not finite");
  if (timed_out_) {
    timed_out_ = false;
    report(Severity::Notice, ErrorType::Timeout, kErrCommandTimeout, "LL_CMD_MOTION again: propulsion resumes");
  }

  const double v = std::clamp(speed, -cfg_.max_speed_mps, cfg_.max_speed_mps);
  if (v != speed) {
    if (!warned_speed_clamp_)
      report(Severity::Warning, ErrorType::Unknown, kErrClamped,
             "speed " + fmt("%.3f", speed) + " m/s beyond the limit, clamped to " + fmt("%.3f", v) + " m/s");
    warned_speed_clamp_ = true;
  } else {
    warned_speed_clamp_ = false;
  }
  pending_speed_ = v;
  ensure_enabled(prop_);

  // During homing (or while it waits for the enable) the target is held, not
  // refused: the latest one is applied once the IclA is back in profile position.
  const bool homing_runs = homing_ || homing_requested_;
  if (!homed_ && !homing_runs) {
    if (!warned_not_homed_)
      report(Severity::Warning, ErrorType::Unknown, kErrNotHomed,
             "steering target refused: the steering is not homed (LL_CMD_HOMING axis=steering)");
    warned_not_homed_ = true;
    return;
  }
  const double lim = cfg_.steering_limit_rad;
  const double s = std::clamp(steering, -lim, lim);
  if (s != steering) {
    if (!warned_clamp_)
      report(Severity::Warning, ErrorType::Unknown, kErrClamped,
             "steering " + fmt("%.4f", steering) + " rad beyond the limit, clamped to " + fmt("%.4f", s) + " rad");
    warned_clamp_ = true;
  } else {
    warned_clamp_ = false;
  }
  pending_steering_ = s;
  if (homing_runs) return;
  ensure_enabled(steer_);
}

void DriveController::send_pending_steering(bool retry) {
  if (!pending_steering_ || moving_ || held() || homing_ || homing_requested_ || !homed_) return;
  if (steer_.drive->axis().state() != State::kOperationEnabled) return;
  if (steer_.drive->mode() != canopen::cia402::Mode::kProfilePosition) return;
  const double rad = *pending_steering_;
  pending_steering_.reset();
  cmd_steering_ = rad;
  // The same target again (every command at 10 Hz): the drive is there or on its way.
  if (sent_steering_ && std::abs(rad - *sent_steering_) * std::abs(cfg_.icla.units_per_rad) < 0.5) return;
  moving_ = true;
  sent_steering_ = rad;
  icla_.set_angle(rad, [this, rad, retry](std::error_code ec) {
    moving_ = false;
    if (ec == AxisError::kSetPointTimeout && !retry && steer_.online && !held()) {
      // One more handshake before giving up; a newer target wins over this one.
      sent_steering_.reset();
      if (!pending_steering_) pending_steering_ = rad;
      return send_pending_steering(true);
    }
    if (ec) {
      sent_steering_.reset();
      if (ec != AxisError::kCancelled && steer_.online && !held())
        report(Severity::Error, ErrorType::Device, kErrDrive, steer_.name + ": steering move failed: " + ec.message());
      return;
    }
    send_pending_steering();
  });
}

void DriveController::home_steering() {
  if (!started_ || !steer_.online) {
    report(Severity::Warning, ErrorType::Unknown, kErrRefused, "LL_CMD_HOMING refused: " + steer_.name + " offline");
    return;
  }
  if (held()) {
    report(Severity::Warning, ErrorType::Unknown, kErrRefused,
           std::string("LL_CMD_HOMING refused: ") + (paused_ ? "module paused" : "LL_EVENT_STOP engaged"));
    return;
  }
  if (homing_ || homing_requested_) {
    // The planner's request during the start-up homing: restarting it would
    // only throw away the progress, so it joins the running one.
    if (!homing_joined_)
      report(Severity::Notice, ErrorType::Device, kErrHoming,
             "LL_CMD_HOMING while " + steer_.name + " homes: joins the running homing");
    homing_joined_ = true;
    return;
  }
  homed_ = false;
  homing_joined_ = false;
  homing_requested_ = true;
  ensure_enabled(steer_);
}

void DriveController::start_homing() {
  homing_requested_ = false;
  homing_ = true;
  sent_steering_.reset();
  report(Severity::Notice, ErrorType::Device, kErrHoming, steer_.name + ": homing");
  icla_.home([this](std::error_code ec) {
    homing_ = false;
    moving_ = false;
    if (ec) {
      pending_steering_.reset();  // held for a homed steering only
      report(Severity::Error, ErrorType::Device, kErrHoming, steer_.name + ": homing failed: " + ec.message());
      return;
    }
    homed_ = true;
    warned_not_homed_ = false;
    const auto a = icla_.angle();
    sent_steering_ = a;
    cmd_steering_ = a.value_or(0);
    report(Severity::Notice, ErrorType::Device, kErrHoming,
           steer_.name + ": homed, steering at " + fmt("%.4f", a.value_or(0)) + " rad");
    send_pending_steering();  // the latest target that arrived during the homing
  });
}

void DriveController::quick_stop_propulsion(const std::string& why) {
  pending_speed_.reset();
  cmd_speed_ = 0;
  if (!prop_.online) return;
  // Target 0 first: a later re-enable must not resume the old speed.
  epos_.drive().set_target(0x60FF, 0, 0);
  epos_.quick_stop([this, why](std::error_code ec) {
    if (ec && ec != AxisError::kCancelled && prop_.online)
      report(Severity::Error, ErrorType::Device, kErrDrive, prop_.name + ": quick stop (" + why + ") failed: " + ec.message());
  });
}

void DriveController::quick_stop_all(const std::string& why) {
  quick_stop_propulsion(why);
  pending_steering_.reset();
  sent_steering_.reset();
  homing_requested_ = false;
  if (!steer_.online) return;
  icla_.drive().quick_stop([this, why](std::error_code ec) {
    if (ec && ec != AxisError::kCancelled && steer_.online)
      report(Severity::Error, ErrorType::Device, kErrDrive, steer_.name + ": quick stop (" + why + ") failed: " + ec.message());
  });
}

void DriveController::stop_event(bool engaged) {
  if (engaged == stop_engaged_) return;
  stop_engaged_ = engaged;
  warned_refused_ = false;
  if (engaged) {
    report(Severity::Notice, ErrorType::Unknown, kErrStop, "LL_EVENT_STOP engaged: quick stop, no motion until released");
    quick_stop_all("LL_EVENT_STOP");
  } else {
    report(Severity::Notice, ErrorType::Unknown, kErrStop, "LL_EVENT_STOP released: the next LL_CMD_MOTION moves");
  }
}

void DriveController::pause() {
  if (paused_) return;
  paused_ = true;
  quick_stop_all("module paused");
}

void DriveController::resume() { paused_ = false; }

DrivesStatus DriveController::status() const {
  DrivesStatus s;
  auto fill = [](const Unit& u, DriveStatus& d, std::uint8_t node) {
    d.axis = u.axis;
    d.node = node;
    d.error_code = u.emcy;
    if (!u.online || !u.drive->axis().has_statusword()) {
      d.state = "offline";
      return;
    }
    const State st = u.drive->axis().state();
    d.state = std::string(canopen::cia402::to_string(st));
    d.fault = st == State::kFault || st == State::kFaultReactionActive;
  };
  fill(prop_, s.drives[0], cfg_.epos.node);
  fill(steer_, s.drives[1], cfg_.icla.node);
  s.drives[1].homed = homed_;
  if (prop_.online) s.speed_mps = epos_.speed().value_or(0);
  if (steer_.online) s.steering_rad = icla_.angle().value_or(0);
  s.cmd_speed_mps = cmd_speed_;
  s.cmd_steering_rad = cmd_steering_;
  const bool fault = s.drives[0].fault || s.drives[1].fault;
  if (paused_)
    s.stop_reason = "module paused";
  else if (stop_engaged_)
    s.stop_reason = "LL_EVENT_STOP";
  else if (!started_)
    s.stop_reason = "booting";
  else if (!prop_.online || !steer_.online)
    s.stop_reason = "drive offline";
  else if (fault)
    s.stop_reason = "fault";
  else if (timed_out_)
    s.stop_reason = "command timeout";
  else if (prop_.drive->axis().state() != State::kOperationEnabled)
    s.stop_reason = "propulsion not enabled";
  s.stopped = !s.stop_reason.empty();
  return s;
}

void DriveController::poll() {
  const auto now = master_.now();
  for (Unit* u : {&prop_, &steer_}) {
    if (!u->reboot_at || now < *u->reboot_at || u->booting) continue;
    u->reboot_at.reset();
    boot(*u, [this, u](bool ok) {
      if (!ok) return;
      ensure_enabled(*u);
      if (u->axis == Axis::kSteering && cfg_.home_on_start) home_steering();
    });
  }
}

std::optional<canopen::TimePoint> DriveController::deadline() const {
  std::optional<canopen::TimePoint> d;
  for (const Unit* u : {&prop_, &steer_})
    if (u->reboot_at && (!d || *u->reboot_at < *d)) d = u->reboot_at;
  return d;
}

}  // namespace advee::driver_canbus
