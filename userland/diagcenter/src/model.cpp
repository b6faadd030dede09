// SPDX-License-Identifier: GPL-2.0
#include "advee/diagcenter/model.hpp"

#include <algorithm>
#include <cmath>

#include "advee/msgs/channels.hpp"
#include "common/data_module_phase_t.hpp"
#include "common/data_state_t.hpp"

namespace advee::diagcenter {

namespace {

template <typename Msg>
bool decode_into(const void* data, std::size_t size, Msg& m) {
  return m.decode(data, 0, static_cast<int>(size)) >= 0;
}

template <typename Msg>
bool take(Latest<Msg>& slot, const void* data, std::size_t size, double now) {
  Msg m{};
  if (!decode_into(data, size, m)) return false;
  slot.msg = std::move(m);
  slot.at = now;
  return true;
}

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
  v.emplace_back(kSimPoseChannel);
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
    common::data_state_t s{};
    if ((ok = decode_into(data, size, s))) {
      auto& m = module_named(s.module);
      m.state = module::state_from_wire(s.state);
      if (m.pid != s.pid) ++m.pids_seen;
      m.pid = s.pid;
      m.state_at = now;
    }
  } else if (ch == msgs::kDataModules.name) {
    common::data_module_phase_t p{};
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
  } else if (ch == kSimPoseChannel) {
    sim::data_pose_t p{};
    if ((ok = decode_into(data, size, p))) {
      true_pose_.x_m = p.x_m;
      true_pose_.y_m = p.y_m;
      true_pose_.heading_rad = p.heading_rad;
      true_pose_.speed_mps = p.speed_mps;
      true_pose_.steering_rad = p.steering_rad;
      true_pose_.at = now;
      if (!odo_from_truth_) {
        // The first ground truth: the estimate continues from there.
        odo_pose_.reset({p.x_m, p.y_m, p.heading_rad});
        odo_from_truth_ = true;
      }
    }
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

void Model::reset_odometry() {
  if (true_pose_.has())
    odo_pose_.reset({true_pose_.x_m, true_pose_.y_m, true_pose_.heading_rad});
  else
    odo_pose_.reset();
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
