// SPDX-License-Identifier: GPL-2.0
// The robot description file (docs/robotsim.md): chassis, start pose, sensor
// placement and models, thermal channels. Absent fields keep the defaults of
// robot.hpp; sensors and thermal channels must be listed.
#include <set>
#include <utility>

#include "advee/robotsim/robot.hpp"
#include "yaml_util.hpp"

namespace advee::robotsim {

namespace {

using yaml::Ctx;

void positive(const Ctx& c, const YAML::Node& parent, const std::string& key, const std::string& section,
              double& value) {
  value = yaml::number_or(c, parent, key, section + "." + key, value);
  if (!(value > 0)) c.fail(parent[key], section + "." + key, "must be > 0");
}

void check_keys(const Ctx& c, const YAML::Node& n, const std::string& section, std::set<std::string> allowed) {
  if (!n.IsMap()) c.fail(n, section, "expected a mapping");
  for (const auto& kv : n) {
    const std::string key = kv.first.as<std::string>();
    if (!allowed.count(key)) c.fail(kv.first, section + "." + key, "unknown field");
  }
}

std::vector<RangeSensor> read_sensors(const Ctx& c, const YAML::Node& parent, const std::string& section,
                                      int per_board, bool with_heading) {
  const YAML::Node list = yaml::need(c, parent, "sensors", section + ".sensors");
  if (!list.IsSequence()) c.fail(list, section + ".sensors", "expected a list");
  std::vector<RangeSensor> out;
  std::set<std::pair<int, int>> seen;
  for (std::size_t i = 0; i < list.size(); ++i) {
    const YAML::Node& n = list[i];
    const std::string f = section + ".sensors[" + std::to_string(i) + "]";
    RangeSensor s;
    const YAML::Node board = yaml::need(c, n, "board", f + ".board");
    const std::string b = board.IsScalar() ? board.Scalar() : "";
    if (b != "front" && b != "rear") c.fail(board, f + ".board", "expected front or rear");
    s.board = b == "front" ? 0 : 1;
    s.index = static_cast<int>(yaml::integer(c, yaml::need(c, n, "index", f + ".index"), f + ".index", 0,
                                             per_board - 1));
    if (!seen.insert({s.board, s.index}).second) c.fail(n, f, "board " + b + " index " + std::to_string(s.index) + " listed twice");
    s.position = {yaml::number(c, yaml::need(c, n, "x", f + ".x"), f + ".x"),
                  yaml::number(c, yaml::need(c, n, "y", f + ".y"), f + ".y")};
    if (with_heading) s.heading_deg = yaml::number(c, yaml::need(c, n, "heading_deg", f + ".heading_deg"), f + ".heading_deg");
    out.push_back(s);
  }
  return out;
}

}  // namespace

RobotDescription parse_robot(const std::string& text, const std::string& name) {
  const Ctx c{name};
  const YAML::Node doc = yaml::parse(text, name);
  check_keys(c, doc, "robot", {"chassis", "start", "srf", "ir", "beacon_scanner", "thermal", "drives"});
  RobotDescription d;

  if (const YAML::Node ch = doc["chassis"]) {
    check_keys(c, ch, "chassis", {"wheelbase_m", "track_m", "wheel_radius_m", "ticks_per_rev", "max_steering_deg",
                                  "max_speed_mps", "front_m", "rear_m", "half_width_m"});
    auto& k = d.chassis;
    for (auto [key, v] : {std::pair{"wheelbase_m", &k.wheelbase_m}, {"track_m", &k.track_m},
                          {"wheel_radius_m", &k.wheel_radius_m}, {"ticks_per_rev", &k.ticks_per_rev},
                          {"max_steering_deg", &k.max_steering_deg}, {"max_speed_mps", &k.max_speed_mps},
                          {"front_m", &k.front_m}, {"rear_m", &k.rear_m}, {"half_width_m", &k.half_width_m}})
      positive(c, ch, key, "chassis", *v);
    // Beyond this the front-wheel odometry has two solutions (kinematics.hpp).
    const double limit = rad_to_deg(std::atan(k.wheelbase_m / std::sqrt(k.wheelbase_m * k.wheelbase_m +
                                                                        k.track_m * k.track_m / 4)));
    if (k.max_steering_deg >= limit)
      c.fail(ch["max_steering_deg"], "chassis.max_steering_deg",
             "must be below " + std::to_string(limit) + " for this wheelbase and track");
  }
  if (const YAML::Node st = doc["start"]) {
    check_keys(c, st, "start", {"x", "y", "heading_deg"});
    d.start.position = {yaml::number_or(c, st, "x", "start.x", 0), yaml::number_or(c, st, "y", "start.y", 0)};
    d.start.heading = deg_to_rad(yaml::number_or(c, st, "heading_deg", "start.heading_deg", 0));
  }
  const YAML::Node srf = yaml::need(c, doc, "srf", "srf");
  check_keys(c, srf, "srf", {"min_m", "max_m", "noise_m", "beam_half_angle_deg", "proximity_pause_m", "sensors"});
  positive(c, srf, "min_m", "srf", d.srf.min_m);
  positive(c, srf, "max_m", "srf", d.srf.max_m);
  d.srf.noise_m = yaml::number_or(c, srf, "noise_m", "srf.noise_m", d.srf.noise_m);
  d.srf.beam_half_angle_deg = yaml::number_or(c, srf, "beam_half_angle_deg", "srf.beam_half_angle_deg",
                                              d.srf.beam_half_angle_deg);
  d.srf.proximity_pause_m = yaml::number_or(c, srf, "proximity_pause_m", "srf.proximity_pause_m", 0);
  d.srf.sensors = read_sensors(c, srf, "srf", 8, true);

  const YAML::Node ir = yaml::need(c, doc, "ir", "ir");
  check_keys(c, ir, "ir", {"min_m", "max_m", "ground_m", "noise_m", "pause_deviation_m", "sensors"});
  positive(c, ir, "min_m", "ir", d.ir.min_m);
  positive(c, ir, "max_m", "ir", d.ir.max_m);
  positive(c, ir, "ground_m", "ir", d.ir.ground_m);
  positive(c, ir, "pause_deviation_m", "ir", d.ir.pause_deviation_m);
  d.ir.noise_m = yaml::number_or(c, ir, "noise_m", "ir.noise_m", d.ir.noise_m);
  d.ir.sensors = read_sensors(c, ir, "ir", 2, false);

  if (const YAML::Node sc = doc["beacon_scanner"]) {
    check_keys(c, sc, "beacon_scanner", {"x", "y", "max_range_m", "noise_deg"});
    d.scanner.position = {yaml::number_or(c, sc, "x", "beacon_scanner.x", 0),
                          yaml::number_or(c, sc, "y", "beacon_scanner.y", 0)};
    positive(c, sc, "max_range_m", "beacon_scanner", d.scanner.max_range_m);
    d.scanner.noise_deg = yaml::number_or(c, sc, "noise_deg", "beacon_scanner.noise_deg", d.scanner.noise_deg);
  }
  if (const YAML::Node th = doc["thermal"]) {
    if (!th.IsSequence() || th.size() > 2) c.fail(th, "thermal", "expected a list of at most 2 channels (temp1, temp2)");
    for (std::size_t i = 0; i < th.size(); ++i) {
      const std::string f = "thermal[" + std::to_string(i) + "]";
      check_keys(c, th[i], f, {"load", "ambient_c", "gain_c", "tau_s"});
      ThermalChannel ch;
      const YAML::Node load = yaml::need(c, th[i], "load", f + ".load");
      const std::string l = load.IsScalar() ? load.Scalar() : "";
      if (l != "propulsion" && l != "steering") c.fail(load, f + ".load", "expected propulsion or steering");
      ch.load = l == "propulsion" ? ThermalChannel::Load::kPropulsion : ThermalChannel::Load::kSteering;
      ch.ambient_c = yaml::number_or(c, th[i], "ambient_c", f + ".ambient_c", ch.ambient_c);
      ch.gain_c = yaml::number_or(c, th[i], "gain_c", f + ".gain_c", ch.gain_c);
      positive(c, th[i], "tau_s", f, ch.tau_s);
      d.thermal.push_back(ch);
    }
  }
  if (const YAML::Node dr = doc["drives"]) {
    check_keys(c, dr, "drives", {"propulsion", "steering"});
    auto& u = d.drives;
    const auto node = [&](const YAML::Node& parent, const std::string& section, std::uint8_t& v) {
      if (parent["node"]) v = static_cast<std::uint8_t>(yaml::integer(c, parent["node"], section + ".node", 1, 127));
    };
    if (const YAML::Node p = dr["propulsion"]) {
      check_keys(c, p, "drives.propulsion", {"node", "gear_ratio", "wheel_radius_m"});
      node(p, "drives.propulsion", u.propulsion_node);
      positive(c, p, "gear_ratio", "drives.propulsion", u.gear_ratio);
      positive(c, p, "wheel_radius_m", "drives.propulsion", u.drive_wheel_radius_m);
    }
    if (const YAML::Node st = dr["steering"]) {
      check_keys(c, st, "drives.steering", {"node", "units_per_rad", "home_switch_deg", "start_deg"});
      node(st, "drives.steering", u.steering_node);
      positive(c, st, "units_per_rad", "drives.steering", u.steering_units_per_rad);
      u.home_switch_deg = yaml::number_or(c, st, "home_switch_deg", "drives.steering.home_switch_deg", u.home_switch_deg);
      u.start_steering_deg = yaml::number_or(c, st, "start_deg", "drives.steering.start_deg", u.start_steering_deg);
    }
    if (u.propulsion_node == u.steering_node)
      c.fail(dr, "drives", "propulsion and steering need different node-IDs");
  }
  if (d.srf.noise_m < 0) c.fail(srf["noise_m"], "srf.noise_m", "must be >= 0");
  if (d.ir.noise_m < 0) c.fail(ir["noise_m"], "ir.noise_m", "must be >= 0");
  if (d.scanner.noise_deg < 0) c.fail(doc["beacon_scanner"]["noise_deg"], "beacon_scanner.noise_deg", "must be >= 0");
  return d;
}

RobotDescription load_robot(const std::string& path) { return parse_robot(yaml::read_file(path), path); }

}  // namespace advee::robotsim
