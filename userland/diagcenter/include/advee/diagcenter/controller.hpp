// SPDX-License-Identifier: GPL-2.0
// Keys -> commands and view state, without a terminal: the ncurses view
// translates its key codes into Key and draws what the controller holds.
//
//   1..4 / F1..F4   summary, errors, modules, power view
//   q               quit (a manual drive is stopped first)
//   space           stop: speed and steering 0 at once (every view)
//   summary:  arrows drive (the first one switches manual driving on),
//             m manual driving on/off, h home the steering, o reset odometry
//   errors:   up/down scroll, c clear
//   modules:  up/down select, r RUN, p PAUSE, s STOP, t t TERMINATE
//             (twice within 3 s: it keeps the module down)
//   power:    up/down select, enter toggle, n on, f off
//
// While manual driving is on, tick() repeats LL_CMD_MOTION every
// kMotionRepeatS (10 Hz): driver_canbus quick-stops after 1 s without one.
#pragma once

#include <string>

#include "advee/diagcenter/commands.hpp"
#include "advee/diagcenter/model.hpp"

namespace advee::diagcenter {

struct Key {
  enum Kind { Char, Up, Down, Left, Right, Enter, Function, Resize, None };
  Kind kind = None;
  int value = 0;  // the character (Char) or the function key number (Function)
  static Key ch(int c) { return {Char, c}; }
  static Key fn(int n) { return {Function, n}; }
};

enum class View { Summary, Errors, Modules, Power };
inline constexpr int kViewCount = 4;
const char* view_name(View v);

struct DriveLimits {
  double speed_step_mps = 0.1;
  double max_speed_mps = 1.0;
  double steering_step_rad = 0.0872664626;  // 5 degrees
  double max_steering_rad = 0.5235987756;   // 30 degrees, the IclA's limit
};

class Controller {
 public:
  static constexpr double kMotionRepeatS = 0.1;
  static constexpr int kDefaultPowerOutputs = 8;  // the PSC1's
  static constexpr double kConfirmS = 3.0;        // TERMINATE: second t within this

  Controller(Model& model, CommandSink& sink, DriveLimits limits = {})
      : model_(model), sink_(sink), limits_(limits) {}

  // One key at time `now` (monotonic seconds). Returns true when it changed
  // something the view shows (so it redraws).
  bool on_key(const Key& k, double now);
  // Repeat the manual motion command when due. Call often (>= 10 Hz).
  void tick(double now);
  // Stop a manual drive (zero command) before quitting.
  void shutdown();

  View view() const { return view_; }
  bool quit() const { return quit_; }
  bool manual() const { return manual_; }
  double speed_mps() const { return speed_; }
  double steering_rad() const { return steering_; }
  const DriveLimits& limits() const { return limits_; }
  // Selected row of the modules view (an index into model.modules()), clamped.
  std::size_t module_row() const;
  std::string selected_module() const;  // "" when there is none
  int power_row() const { return power_row_; }
  int power_outputs() const;
  std::size_t error_scroll() const { return error_scroll_; }  // rows hidden below the newest
  const std::string& status() const { return status_; }       // the last action, for the status line
  unsigned long motions_sent() const { return motions_sent_; }

 private:
  bool summary_key(const Key& k, double now);
  bool errors_key(const Key& k);
  bool modules_key(const Key& k, double now);
  bool power_key(const Key& k);
  void send_motion(double now);
  void publish_motion();
  void set_state(module::State s);

  Model& model_;
  CommandSink& sink_;
  DriveLimits limits_;
  View view_ = View::Summary;
  bool quit_ = false;
  bool manual_ = false;
  double speed_ = 0;
  double steering_ = 0;
  double next_motion_at_ = 0;
  std::size_t module_row_ = 0;
  int power_row_ = 0;
  std::size_t error_scroll_ = 0;
  std::string status_;
  std::string confirm_target_;  // TERMINATE asked once for this module ...
  double confirm_until_ = 0;    // ... and confirmed by a second t until then
  unsigned long motions_sent_ = 0;
};

}  // namespace advee::diagcenter
