// SPDX-License-Identifier: GPL-2.0
#include "advee/web/odometry.hpp"

namespace advee::web {

nlohmann::json OdometryIntegrator::to_json(long long utime) const {
  const Pose2 p = pose();
  return {{"channel", kOdoPoseChannel}, {"utime", utime}, {"x_m", p.x}, {"y_m", p.y}, {"heading_rad", p.heading}};
}

}  // namespace advee::web
