// SPDX-License-Identifier: GPL-2.0
// The diagnostic centre's picture of the robot: the newest message of every
// low-level channel, the modules (their own CM_DATA_STATE announcements
// merged with the supervisor's CM_DATA_MODULES), the recent error reports and
// the odometry position estimate. It only decodes and aggregates; the
// terminal view and the text summary read it, so it is tested without a
// terminal by feeding it encoded messages.
//
// Times are seconds of a monotonic clock given by the caller (receive
// times), so that "stale" means "not heard from for a while" whatever the
// senders' clocks say.
#pragma once

#include <cstdint>
#include <deque>
#include <lcm/lcm-cpp.hpp>
#include <limits>
#include <map>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "advee/pose_integrator.hpp"
#include "advee/module/state.hpp"
#include "common/error_t.hpp"
#include "lowlevel/cmd_homing_t.hpp"
#include "lowlevel/cmd_motion_t.hpp"
#include "lowlevel/cmd_power_t.hpp"
#include "lowlevel/data_beacons_t.hpp"
#include "lowlevel/data_drives_t.hpp"
#include "lowlevel/data_fans_t.hpp"
#include "lowlevel/data_odo_t.hpp"
#include "lowlevel/data_power_t.hpp"
#include "lowlevel/data_srfs_t.hpp"
#include "lowlevel/data_temperature_t.hpp"
#include "lowlevel/event_stop_t.hpp"

#include "sim/data_pose_t.hpp"

namespace advee::diagcenter {

inline constexpr double kNever = -std::numeric_limits<double>::infinity();

// The newest message of one channel and when it arrived.
template <typename Msg>
struct Latest {
  Msg msg{};
  double at = kNever;
  bool has() const { return at != kNever; }
  double age(double now) const { return now - at; }
};

// One module as the announcements and the supervisor describe it.
struct ModuleInfo {
  std::string name;
  // CM_DATA_STATE (the module itself)
  std::optional<module::State> state;
  std::int32_t pid = 0;
  double state_at = kNever;
  // CM_DATA_MODULES (the supervisor); phase -1 = the supervisor said nothing yet
  int phase = -1;
  std::int32_t supervisor_pid = 0;
  std::int32_t restarts = -1;  // -1 unknown
  std::int32_t exit_status = -1;
  std::int32_t next_start_ms = -1;
  double phase_at = kNever;
  int pids_seen = 0;  // distinct pids announced since we started watching
};

struct ErrorEntry {
  double at = kNever;
  common::error_t msg{};
};

// Ground truth of the simulated robot (SIM_DATA_POSE), when the simulator publishes it.
struct TruePose {
  double x_m = 0, y_m = 0, heading_rad = 0;
  double speed_mps = 0, steering_rad = 0;
  double at = kNever;
  bool has() const { return at != kNever; }
};

// Seconds without a message after which a channel of nominal rate rate_hz is
// shown as stale: three periods, at least 1.5 s. Module announcements (1 Hz)
// are stale after 2 s, the supervisor's dead_after_s.
double stale_after_s(double rate_hz);
inline constexpr double kModuleStaleAfterS = 2.0;

const char* phase_name(int phase);  // CM_DATA_MODULES phases, "-" for -1

class Model {
 public:
  static constexpr std::size_t kMaxErrors = 200;

  Model();
  ~Model();  // unsubscribes from the LCM given to subscribe()
  Model(const Model&) = delete;
  Model& operator=(const Model&) = delete;

  // Decode one message of `channel` received at `now`. Returns false for
  // channels the model does not know and for messages that do not decode
  // (counted in decode_failures()).
  bool handle(const std::string& channel, const void* data, std::size_t size, double now);

  // Subscribe every channel the model knows on `lcm` (messages go to
  // handle() with clock() as receive time). The subscriptions live as long
  // as the LCM object; call once.
  void subscribe(lcm::LCM& lcm, double (*clock)());

  const std::map<std::string, ModuleInfo>& modules() const { return modules_; }
  const std::deque<ErrorEntry>& errors() const { return errors_; }  // oldest first
  std::uint64_t errors_total() const { return errors_total_; }
  void clear_errors() { errors_.clear(); }

  // The position estimate. It starts at 0, 0, heading 0 - or, on the
  // simulated robot, at the first ground-truth pose (SIM_DATA_POSE), so that
  // both are in the world frame and can be compared directly.
  const PoseIntegrator& odometry() const { return odo_pose_; }
  bool odometry_from_true_pose() const { return odo_from_truth_; }
  // Back to the newest true pose when there is one, else to 0, 0.
  void reset_odometry();

  const Latest<lowlevel::data_odo_t>& odo() const { return odo_; }
  const Latest<lowlevel::cmd_motion_t>& motion_cmd() const { return motion_; }
  const Latest<lowlevel::data_drives_t>& drives() const { return drives_; }
  const Latest<lowlevel::data_srfs_t>& srfs() const { return srfs_; }
  const Latest<lowlevel::data_beacons_t>& beacons() const { return beacons_; }
  const Latest<lowlevel::data_temperature_t>& temperatures() const { return temps_; }
  const Latest<lowlevel::data_fans_t>& fans() const { return fans_; }
  const Latest<lowlevel::data_power_t>& power() const { return power_; }
  const Latest<lowlevel::event_stop_t>& stop_event() const { return stop_; }
  const Latest<lowlevel::cmd_homing_t>& homing_cmd() const { return homing_; }
  const Latest<lowlevel::cmd_power_t>& power_cmd() const { return power_cmd_; }
  const TruePose& true_pose() const { return true_pose_; }

  // PAUSE engaged: the newest of LL_EVENT_STOP and LL_DATA_POWER.paused.
  // nullopt while neither has been heard.
  std::optional<bool> pause_engaged() const;

  std::uint64_t messages() const { return messages_; }  // decoded messages, all channels
  std::uint64_t decode_failures() const { return decode_failures_; }
  double last_message_at() const { return last_at_; }

 private:
  ModuleInfo& module_named(const std::string& name);

  std::map<std::string, ModuleInfo> modules_;
  std::map<std::string, std::int32_t> last_pid_;  // to count pids_seen
  std::deque<ErrorEntry> errors_;
  std::uint64_t errors_total_ = 0;
  PoseIntegrator odo_pose_;
  Latest<lowlevel::data_odo_t> odo_;
  Latest<lowlevel::cmd_motion_t> motion_;
  Latest<lowlevel::data_drives_t> drives_;
  Latest<lowlevel::data_srfs_t> srfs_;
  Latest<lowlevel::data_beacons_t> beacons_;
  Latest<lowlevel::data_temperature_t> temps_;
  Latest<lowlevel::data_fans_t> fans_;
  Latest<lowlevel::data_power_t> power_;
  Latest<lowlevel::event_stop_t> stop_;
  Latest<lowlevel::cmd_homing_t> homing_;
  Latest<lowlevel::cmd_power_t> power_cmd_;
  TruePose true_pose_;
  bool odo_from_truth_ = false;
  std::uint64_t messages_ = 0;
  std::uint64_t decode_failures_ = 0;
  double last_at_ = kNever;

  struct Sub;  // one LCM subscription's context (model + clock + LCM's handle)
  lcm::LCM* lcm_ = nullptr;
  std::vector<std::unique_ptr<Sub>> subs_;
};

inline constexpr const char* kSimPoseChannel = "SIM_DATA_POSE";  // the simulator's ground truth, 10 Hz

// The channels the model subscribes: kAllChannels and SIM_DATA_POSE.
std::vector<std::string> model_channels();

}  // namespace advee::diagcenter
