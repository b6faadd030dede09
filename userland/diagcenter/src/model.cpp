// SPDX-License-Identifier: GPL-2.0
#include "advee/diagcenter/model.hpp"

#include <algorithm>
#include <cmath>

#include "advee/msgs/channels.hpp"
#include "common/data_module_phase_t.hpp"
#include "common/data_state_t.hpp"

namespace advee::diagcenter {

namespace {

constexpr const char* kSimPoseChannel = "SIM_DATA_POSE";

template <typename Msg>
bool decode_into(const void* data, std::size_t size, Msg& m) {
  return m.decode(data, 0, static_cast<int>(size)) >= 0;
}

template <typename Msg>
bool take(Latest<Msg>& slot, const void* data, std::size_t size, double now) {
  Msg m;
  if (!decode_into(data, size, m)) return false;
  slot.msg = std::move(m);
  slot.at = now;
  return true;
}

#if ADVEE_DIAGCENTER_HAVE_SIM_POSE
// The simulator's type is written by another component; read its fields by
// the names it may reasonably use, so that a rename there cannot break this
// build (a field not found reads as NaN and shows as such).
#define ADVEE_FIELD_OR_NAN(fn, ...)                                            \
  template <typename P>                                                       \
  double fn(const P& p) {                                                     \
    __VA_ARGS__                                                               \
    return std::nan("");                                                      \
  }
#define ADVEE_TRY(f) \
  if constexpr (requires { p.f; }) return static_cast<double>(p.f);
ADVEE_FIELD_OR_NAN(pose_x, ADVEE_TRY(x_m) else ADVEE_TRY(x))
ADVEE_FIELD_OR_NAN(pose_y, ADVEE_TRY(y_m) else ADVEE_TRY(y))
ADVEE_FIELD_OR_NAN(pose_heading, ADVEE_TRY(heading_rad) else ADVEE_TRY(theta_rad) else ADVEE_TRY(yaw_rad) else ADVEE_TRY(heading))
ADVEE_FIELD_OR_NAN(pose_speed, ADVEE_TRY(speed_mps) else ADVEE_TRY(v_mps))
ADVEE_FIELD_OR_NAN(pose_steering, ADVEE_TRY(steering_rad) else ADVEE_TRY(steer_rad))
#undef ADVEE_TRY
#undef ADVEE_FIELD_OR_NAN
#endif

}  // namespace

double stale_after_s(double rate_hz) {
  if (rate_hz <= 0) return std::numeric_limits<double>::infinity();
  return std::max(1.5, 3.0 / rate_hz);
}

const char* phase_name(int phase) {
  static const char* names[] = {"DOWN", "STARTING", "RUNNING", "TERMINATING", "TERMINATED"};
  if (phase < 0) return "-";
  return phase < 5 ? names[phase] : "?";
}

std::vector<std::string> model_channels() {
  std::vector<std::string> v;
  for (const auto& c : msgs::kAllChannels) v.emplace_back(c.name);
  if (Model::kHaveTruePose) v.emplace_back(kSimPoseChannel);
  return v;
}

ModuleInfo& Model::module_named(const std::string& name) {
  auto& m = modules_[name];
  m.name = name;
  return m;
}

bool Model::handle(const std::string& ch, const void* data, std::size_t size, double now) {
  bool ok = false;
  bool known = true;
  if (ch == msgs::kDataState.name) {
    common::data_state_t s;
    if ((ok = decode_into(data, size, s))) {
      auto& m = module_named(s.module);
      m.state = module::state_from_wire(s.state);
      if (m.pid != s.pid) ++m.pids_seen;
      m.pid = s.pid;
      m.state_at = now;
    }
  } else if (ch == msgs::kDataModules.name) {
    common::data_module_phase_t p;
    if ((ok = decode_into(data, size, p))) {
      auto& m = module_named(p.target);
      m.phase = p.phase;
      m.supervisor_pid = p.pid;
      m.restarts = p.restarts;
      m.exit_status = p.exit_status;
      m.next_start_ms = p.next_start_ms;
      m.phase_at = now;
    }
  } else if (ch == msgs::kDataError.name) {
    ErrorEntry e;
    if ((ok = decode_into(data, size, e.msg))) {
      e.at = now;
      errors_.push_back(std::move(e));
      ++errors_total_;
      while (errors_.size() > kMaxErrors) errors_.pop_front();
    }
  } else if (ch == msgs::kDataOdo.name) {
    if ((ok = take(odo_, data, size, now)))
      odo_pose_.advance(odo_.msg.speed_mps, odo_.msg.yaw_rate_radps, odo_.msg.interval_s);
  } else if (ch == msgs::kCmdMotion.name) {
    ok = take(motion_, data, size, now);
  } else if (ch == msgs::kDataDrives.name) {
    ok = take(drives_, data, size, now);
  } else if (ch == msgs::kDataSrfs.name) {
    ok = take(srfs_, data, size, now);
  } else if (ch == msgs::kDataBeacons.name) {
    ok = take(beacons_, data, size, now);
  } else if (ch == msgs::kDataTemperature.name) {
    ok = take(temps_, data, size, now);
  } else if (ch == msgs::kDataFans.name) {
    ok = take(fans_, data, size, now);
  } else if (ch == msgs::kDataPower.name) {
    ok = take(power_, data, size, now);
  } else if (ch == msgs::kEventStop.name) {
    ok = take(stop_, data, size, now);
  } else if (ch == msgs::kCmdHoming.name) {
    ok = take(homing_, data, size, now);
  } else if (ch == msgs::kCmdPower.name) {
    ok = take(power_cmd_, data, size, now);
  } else if (ch == msgs::kCmdState.name || ch == msgs::kDataActiveBeacons.name) {
    ok = true;  // seen (counts as traffic); nothing of it is shown
#if ADVEE_DIAGCENTER_HAVE_SIM_POSE
  } else if (ch == kSimPoseChannel) {
    sim::data_pose_t p;
    if ((ok = decode_into(data, size, p))) {
      true_pose_.x_m = pose_x(p);
      true_pose_.y_m = pose_y(p);
      true_pose_.heading_rad = pose_heading(p);
      true_pose_.speed_mps = pose_speed(p);
      true_pose_.steering_rad = pose_steering(p);
      true_pose_.at = now;
    }
#endif
  } else {
    known = false;
  }
  if (!known) return false;
  if (!ok) {
    ++decode_failures_;
    return false;
  }
  ++messages_;
  last_at_ = now;
  return true;
}

std::optional<bool> Model::pause_engaged() const {
  if (!stop_.has() && !power_.has()) return std::nullopt;
  if (stop_.has() && (!power_.has() || stop_.at >= power_.at)) return stop_.msg.stop;
  return power_.msg.paused;
}

struct Model::Sub {
  Model* model;
  double (*clock)();
  lcm::Subscription* handle = nullptr;
  static void on(const lcm::ReceiveBuffer* rb, const std::string& ch, Sub* self) {
    self->model->handle(ch, rb->data, rb->data_size, self->clock());
  }
};

Model::Model() = default;

void Model::subscribe(lcm::LCM& lcm, double (*clock)()) {
  lcm_ = &lcm;
  for (const auto& ch : model_channels()) {
    auto s = std::make_unique<Sub>(Sub{this, clock});
    s->handle = lcm.subscribeFunction(ch, &Sub::on, s.get());
    subs_.push_back(std::move(s));
  }
}

Model::~Model() {
  if (lcm_)
    for (auto& s : subs_)
      if (s->handle) lcm_->unsubscribe(s->handle);
}

}  // namespace advee::diagcenter
