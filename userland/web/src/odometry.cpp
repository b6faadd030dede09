// SPDX-License-Identifier: GPL-2.0
#include "advee/web/odometry.hpp"

#include <cmath>

namespace advee::web {

void OdometryIntegrator::add(double v, double w, double dt) {
  if (!std::isfinite(v) || !std::isfinite(w) || !std::isfinite(dt) || dt <= 0) return;
  const double h = pose_.heading;
  if (std::abs(w) > 1e-9) {
    const double r = v / w;
    pose_.x += r * (std::sin(h + w * dt) - std::sin(h));
    pose_.y -= r * (std::cos(h + w * dt) - std::cos(h));
  } else {
    pose_.x += v * dt * std::cos(h);
    pose_.y += v * dt * std::sin(h);
  }
  pose_.heading = std::remainder(h + w * dt, 2 * M_PI);
}

nlohmann::json OdometryIntegrator::to_json(long long utime) const {
  return {{"channel", kOdoPoseChannel},
          {"utime", utime},
          {"x_m", pose_.x},
          {"y_m", pose_.y},
          {"heading_rad", pose_.heading}};
}

}  // namespace advee::web
