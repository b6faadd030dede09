// SPDX-License-Identifier: GPL-2.0
#include "advee/pose_integrator.hpp"

#include <cmath>
#include <numbers>

namespace advee {

double wrap_angle(double rad) {
  double a = std::remainder(rad, 2 * std::numbers::pi);  // [-pi, pi]
  if (a <= -std::numbers::pi) a += 2 * std::numbers::pi;
  return a;
}

void PoseIntegrator::advance(double v, double w, double dt) {
  if (!std::isfinite(v) || !std::isfinite(w) || !std::isfinite(dt) || dt <= 0) return;
  const double h0 = pose_.heading_rad;
  const double dh = w * dt;
  if (std::abs(dh) < 1e-9) {
    // Straight: the arc formula divides by w.
    pose_.x_m += v * dt * std::cos(h0);
    pose_.y_m += v * dt * std::sin(h0);
  } else {
    const double r = v / w;
    pose_.x_m += r * (std::sin(h0 + dh) - std::sin(h0));
    pose_.y_m += -r * (std::cos(h0 + dh) - std::cos(h0));
  }
  pose_.heading_rad = wrap_angle(h0 + dh);
  distance_m_ += std::abs(v) * dt;
}

}  // namespace advee
