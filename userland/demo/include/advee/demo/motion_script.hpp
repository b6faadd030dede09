// SPDX-License-Identifier: GPL-2.0
// The planner stand-in of the demo: a scripted path (robotsim's path file,
// speed/steering/duration segments) turned into the LL_CMD_MOTION commands
// that a planner would send, one per period.
#pragma once

#include <cstddef>
#include <optional>

#include "advee/robotsim/scripted_path.hpp"

namespace advee::demo {

struct MotionCommand {
  double speed_mps = 0;
  double steering_rad = 0;
  std::size_t segment = 0;  // index into the path's segments
};

class MotionScript {
 public:
  explicit MotionScript(robotsim::ScriptedPath path) : path_(std::move(path)) {}

  // The command `t` seconds after the start: the segment that covers t
  // (a segment covers [start, start + duration)); nullopt from the end of
  // the path on (the caller then sends a standstill command).
  std::optional<MotionCommand> at(double t) const;
  double duration() const { return path_.duration(); }
  const robotsim::ScriptedPath& path() const { return path_; }

 private:
  robotsim::ScriptedPath path_;
};

}  // namespace advee::demo
