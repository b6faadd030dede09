// SPDX-License-Identifier: GPL-2.0
#include "advee/diagcenter/controller.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <iterator>
#include <numbers>

namespace advee::diagcenter {

namespace {

// Steps accumulate as binary fractions; snap so that ten 0.1 steps are 1.0
// and a step back returns to exactly 0 (the display shows +0.00, not -0.00).
double snap(double v, double step) { return std::round(v / step) * step; }

std::string fmt_motion(const char* what, double v, double s) {
  char b[96];
  std::snprintf(b, sizeof b, "%s: speed %+.2f m/s, steering %+.1f deg", what, v,
                s * 180 / std::numbers::pi);
  return b;
}

}  // namespace

const char* view_name(View v) {
  switch (v) {
    case View::Summary: return "Summary";
    case View::Errors: return "Errors";
    case View::Modules: return "Modules";
    case View::Power: return "Power";
  }
  return "?";
}

std::size_t Controller::module_row() const {
  const auto n = model_.modules().size();
  return n == 0 ? 0 : std::min(module_row_, n - 1);
}

std::string Controller::selected_module() const {
  const auto& mods = model_.modules();
  if (mods.empty()) return {};
  auto it = mods.begin();
  std::advance(it, static_cast<long>(module_row()));
  return it->first;
}

int Controller::power_outputs() const {
  const auto& p = model_.power();
  return p.has() && p.msg.num_outputs > 0 ? p.msg.num_outputs : kDefaultPowerOutputs;
}

void Controller::send_motion(double now) {
  publish_motion();
  next_motion_at_ = now + kMotionRepeatS;  // a key restarts the 10 Hz schedule
}

void Controller::publish_motion() {
  if (sink_.motion(speed_, steering_))
    ++motions_sent_;
  else
    status_ = "LL_CMD_MOTION could not be published";
}

void Controller::tick(double now) {
  if (!manual_ || now < next_motion_at_) return;
  publish_motion();
  // On the schedule, so that the loop's granularity does not lower the
  // rate; after a long stall (more than a period late) start afresh.
  next_motion_at_ += kMotionRepeatS;
  if (next_motion_at_ <= now) next_motion_at_ = now + kMotionRepeatS;
}

void Controller::shutdown() {
  if (!manual_) return;
  speed_ = steering_ = 0;
  sink_.motion(0, 0);
  manual_ = false;
}

void Controller::set_state(module::State s) {
  const auto target = selected_module();
  if (target.empty()) {
    status_ = "no module to command";
    return;
  }
  const bool ok = sink_.state(target, s);
  status_ = std::string(ok ? "sent " : "could not send ") + std::string(module::to_string(s)) +
            " to " + target;
}

bool Controller::on_key(const Key& k, double now) {
  if (k.kind == Key::Resize) return true;
  if (k.kind == Key::Char && k.value == 'q') {
    shutdown();
    quit_ = true;
    return true;
  }
  int view_no = 0;
  if (k.kind == Key::Function) view_no = k.value;
  if (k.kind == Key::Char && k.value >= '1' && k.value <= '0' + kViewCount) view_no = k.value - '0';
  if (view_no >= 1 && view_no <= kViewCount) {
    view_ = static_cast<View>(view_no - 1);
    return true;
  }
  if (k.kind == Key::Char && k.value == ' ') {
    // Stop works everywhere: whatever view is open, the robot must halt now.
    speed_ = steering_ = 0;
    send_motion(now);
    status_ = fmt_motion("stop", 0, 0);
    return true;
  }
  switch (view_) {
    case View::Summary: return summary_key(k, now);
    case View::Errors: return errors_key(k);
    case View::Modules: return modules_key(k, now);
    case View::Power: return power_key(k);
  }
  return false;
}

bool Controller::summary_key(const Key& k, double now) {
  const auto& l = limits_;
  double v = speed_, s = steering_;
  switch (k.kind) {
    case Key::Up: v = snap(std::min(v + l.speed_step_mps, l.max_speed_mps), l.speed_step_mps); break;
    case Key::Down: v = snap(std::max(v - l.speed_step_mps, -l.max_speed_mps), l.speed_step_mps); break;
    case Key::Left:
      s = snap(std::min(s + l.steering_step_rad, l.max_steering_rad), l.steering_step_rad);
      break;
    case Key::Right:
      s = snap(std::max(s - l.steering_step_rad, -l.max_steering_rad), l.steering_step_rad);
      break;
    case Key::Char:
      if (k.value == 'm') {
        if (manual_) {
          shutdown();
          status_ = "manual driving off (stopped)";
        } else {
          manual_ = true;
          speed_ = steering_ = 0;
          send_motion(now);
          status_ = "manual driving on";
        }
        return true;
      }
      if (k.value == 'h') {
        status_ = sink_.homing_steering() ? "sent steering homing" : "could not send homing";
        return true;
      }
      if (k.value == 'o') {
        model_.reset_odometry();
        status_ = model_.true_pose().has() ? "odometry position reset to the true pose"
                                           : "odometry position reset to 0, 0";
        return true;
      }
      return false;
    default: return false;
  }
  // Limits clamp, they never round the value through zero.
  speed_ = std::clamp(v, -l.max_speed_mps, l.max_speed_mps);
  steering_ = std::clamp(s, -l.max_steering_rad, l.max_steering_rad);
  manual_ = true;
  send_motion(now);
  status_ = fmt_motion("manual", speed_, steering_);
  return true;
}

bool Controller::errors_key(const Key& k) {
  const auto n = model_.errors().size();
  if (k.kind == Key::Up && error_scroll_ + 1 < n) {
    ++error_scroll_;
    return true;
  }
  if (k.kind == Key::Down && error_scroll_ > 0) {
    --error_scroll_;
    return true;
  }
  if (k.kind == Key::Char && k.value == 'c') {
    model_.clear_errors();
    error_scroll_ = 0;
    status_ = "error list cleared";
    return true;
  }
  return false;
}

bool Controller::modules_key(const Key& k, double now) {
  const auto n = model_.modules().size();
  if (k.kind == Key::Up) {
    module_row_ = module_row() > 0 ? module_row() - 1 : 0;
    return true;
  }
  if (k.kind == Key::Down) {
    module_row_ = n > 0 ? std::min(module_row() + 1, n - 1) : 0;
    return true;
  }
  if (k.kind != Key::Char) return false;
  switch (k.value) {
    case 'r': set_state(module::State::Run); return true;
    case 'p': set_state(module::State::Pause); return true;
    case 's': set_state(module::State::Stop); return true;
    case 't': {
      // TERMINATE keeps a module down (and of the supervisor, ends every
      // module): only a second t within kConfirmS sends it.
      const auto target = selected_module();
      if (target.empty() || confirm_target_ != target || now > confirm_until_) {
        confirm_target_ = target;
        confirm_until_ = now + kConfirmS;
        status_ = target.empty() ? "no module to command" : "press t again to TERMINATE " + target;
        return true;
      }
      confirm_target_.clear();
      set_state(module::State::Terminate);
      return true;
    }
    default: return false;
  }
}

bool Controller::power_key(const Key& k) {
  const int n = power_outputs();
  if (k.kind == Key::Up) {
    power_row_ = std::max(0, std::min(power_row_, n - 1) - 1);
    return true;
  }
  if (k.kind == Key::Down) {
    power_row_ = std::min(power_row_ + 1, n - 1);
    return true;
  }
  const int out = std::min(power_row_, n - 1);
  bool on;
  if (k.kind == Key::Enter) {
    const auto& p = model_.power();
    const bool is_on = p.has() && out < p.msg.num_outputs && p.msg.on[static_cast<std::size_t>(out)];
    on = !is_on;
  } else if (k.kind == Key::Char && (k.value == 'n' || k.value == 'f')) {
    on = k.value == 'n';
  } else {
    return false;
  }
  const bool ok = sink_.power_output(out, on);
  status_ = std::string(ok ? "sent" : "could not send") + " output " + std::to_string(out) +
            (on ? " on" : " off");
  return true;
}

}  // namespace advee::diagcenter
