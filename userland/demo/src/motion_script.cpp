// SPDX-License-Identifier: GPL-2.0
#include "advee/demo/motion_script.hpp"

namespace advee::demo {

std::optional<MotionCommand> MotionScript::at(double t) const {
  if (t < 0) return std::nullopt;
  const auto& segs = path_.segments();
  for (std::size_t i = 0; i < segs.size(); ++i) {
    if (t < segs[i].duration_s) return MotionCommand{segs[i].speed_mps, segs[i].steering_rad, i};
    t -= segs[i].duration_s;
  }
  return std::nullopt;
}

}  // namespace advee::demo
