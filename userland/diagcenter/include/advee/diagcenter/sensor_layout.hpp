// SPDX-License-Identifier: GPL-2.0
// Where the range sensors sit on the robot, for drawing the ranges around its
// outline. LL_DATA_SRFS carries only sensor ids; the positions live in
// driver_rs485's configuration (docs/daemons.md). The defaults are those of
// the example robot (userland/daemons/driver_rs485/conf/driver_rs485a.yaml);
// ids not listed are shown as a plain list.
#pragma once

#include <span>

namespace advee::diagcenter {

struct SensorPlace {
  int id;
  double x_m, y_m;    // robot frame: x forward from the rear axle, y left
  double heading_deg;  // beam direction, counter-clockwise from x
};

std::span<const SensorPlace> default_srf_layout();

// The robot's outline in the same frame (for the drawing's scale).
struct Outline {
  double rear_m = -0.25, front_m = 0.90, half_width_m = 0.30;
};

}  // namespace advee::diagcenter
