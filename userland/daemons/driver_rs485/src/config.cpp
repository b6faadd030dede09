// SPDX-License-Identifier: GPL-2.0
#include "advee/driver_rs485/config.hpp"

#include <cmath>
#include <numbers>

namespace advee::driver_rs485 {

using module::ConfigNode;

namespace {

ConfigNode element(const ConfigNode& parent, const YAML::Node& n) { return ConfigNode(n, parent.file()); }

std::uint8_t address(const ConfigNode& n, std::string_view key) {
  const auto a = n.get<unsigned>(key);
  if (a > 0xfe) n.fail(key, "node address must be 0x00..0xfe");
  return static_cast<std::uint8_t>(a);
}

double positive(const ConfigNode& n, std::string_view key, double fallback) {
  const double v = n.get<double>(key, fallback);
  if (!(v > 0) || !std::isfinite(v)) n.fail(key, "must be a positive number");
  return v;
}

std::vector<RangeSensor> sensors(const ConfigNode& board, std::string_view key, unsigned max_index) {
  std::vector<RangeSensor> out;
  if (!board.has(key)) return out;
  const auto list = board.child(key);
  if (!list.yaml().IsSequence()) board.fail(key, "expected a list of {index, id, x, y, heading_deg}");
  for (const auto& y : list.yaml()) {
    const auto s = element(board, y);
    s.allow_only({"index", "id", "x", "y", "heading_deg"});
    RangeSensor r;
    r.index = s.get<unsigned>("index");
    if (r.index > max_index) s.fail("index", "beyond the board's " + std::to_string(max_index + 1) + " sensors");
    r.id = s.get<int>("id");
    if (r.id < 0 || r.id > 32767) s.fail("id", "must be 0..32767");
    r.x_m = s.get<double>("x", 0);
    r.y_m = s.get<double>("y", 0);
    r.heading_rad = s.get<double>("heading_deg", 0) * std::numbers::pi / 180;
    for (const auto& o : out)
      if (o.index == r.index) s.fail("index", "sensor index listed twice");
    out.push_back(r);
  }
  return out;
}

}  // namespace

Rs485Config parse_rs485_config(const ConfigNode& root) {
  root.allow_only({"module", "driver_rs485"});
  Rs485Config c;
  c.module.name = "driver_rs485";
  if (root.has("module")) module::parse_module_options(root.child("module"), c.module);
  const auto n = root.child("driver_rs485");
  n.allow_only({"bus", "rate_hz", "sd1", "so1", "sbs1"});

  // device is required: one instance per bus, no bus to guess.
  c.bus = rs485_daemon::parse_bus_section(n.child("bus"), std::nullopt);

  c.rate_hz = n.get<double>("rate_hz", c.rate_hz);
  if (!(c.rate_hz >= 0.1 && c.rate_hz <= 50)) n.fail("rate_hz", "must be between 0.1 and 50");

  if (n.has("sd1")) {
    const auto list = n.child("sd1");
    if (!list.yaml().IsSequence()) n.fail("sd1", "expected a list of boards");
    for (const auto& y : list.yaml()) {
      const auto e = element(n, y);
      e.allow_only({"name", "address", "srfs", "irs", "first_srf_id", "first_ir_id"});
      Sd1Board s;
      s.address = address(e, "address");
      s.name = e.get<std::string>("name", "sd1@" + std::to_string(s.address));
      s.srfs = sensors(e, "srfs", 7);
      s.irs = sensors(e, "irs", 1);
      s.first_srf_id = e.get<int>("first_srf_id", 0);
      s.first_ir_id = e.get<int>("first_ir_id", 0);
      c.sd1.push_back(std::move(s));
    }
  }
  if (n.has("so1")) {
    const auto e = n.child("so1");
    e.allow_only({"address", "width", "max_speed_mps", "wheel_radius_m", "ticks_per_rev", "track_m", "wheelbase_m", "encoders"});
    So1Board s;
    s.address = address(e, "address");
    s.width = e.get<unsigned>("width", s.width);
    if (s.width != 1 && s.width != 2 && s.width != 4) e.fail("width", "must be 1, 2 or 4");
    auto& g = s.geometry;
    g.wheel_radius_m = positive(e, "wheel_radius_m", g.wheel_radius_m);
    g.ticks_per_rev = positive(e, "ticks_per_rev", g.ticks_per_rev);
    g.track_m = positive(e, "track_m", g.track_m);
    g.wheelbase_m = positive(e, "wheelbase_m", g.wheelbase_m);
    const auto where = e.get<std::string>("encoders", "front");
    if (where != "front" && where != "rear") e.fail("encoders", "front (steered wheels) or rear");
    g.encoders_on_front = where == "front";
    s.max_speed_mps = positive(e, "max_speed_mps", s.max_speed_mps);
    // Gaps beyond the limit are dropped: two poll periods must fit into it,
    // or the odometry would drop most intervals.
    const double gap_s = std::chrono::duration<double>(unambiguous_tick_gap(g, s.width, s.max_speed_mps)).count();
    if (gap_s < 2 / c.rate_hz)
      e.fail("width", std::to_string(s.width) + "-byte counters can wrap ambiguously within " +
                          std::to_string(gap_s) + " s at max_speed_mps: less than two poll periods at rate_hz " +
                          "(use wider counters, a higher rate_hz or a lower max_speed_mps)");
    c.so1 = s;
  }
  if (n.has("sbs1")) {
    const auto e = n.child("sbs1");
    e.allow_only({"address", "beacon_ids", "resend_ids_s"});
    Sbs1Board s;
    s.address = address(e, "address");
    if (e.has("beacon_ids")) {
      const auto ids = e.child("beacon_ids");
      if (!ids.yaml().IsSequence()) e.fail("beacon_ids", "expected a list of ids 0..255");
      for (const auto& y : ids.yaml()) {
        int id = -1;
        try {
          id = y.as<int>();
        } catch (const YAML::Exception&) {
        }
        if (id < 0 || id > 255) e.fail("beacon_ids", "expected a list of ids 0..255");
        s.beacon_ids.push_back(static_cast<std::uint8_t>(id));
      }
    }
    s.resend_ids = e.get_seconds("resend_ids_s", s.resend_ids, 1, 3600);
    c.sbs1 = s;
  }
  if (c.sd1.empty() && !c.so1 && !c.sbs1) n.fail("sd1", "no board configured (sd1, so1 or sbs1)");
  return c;
}

}  // namespace advee::driver_rs485
