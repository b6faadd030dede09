// SPDX-License-Identifier: GPL-2.0
#include "advee/web/control_request.hpp"

#include <cmath>
#include <cstdio>
#include <nlohmann/json.hpp>

#include "common/data_state_t.hpp"

namespace advee::web {

using nlohmann::json;

namespace {

struct StateName {
  const char* name;
  std::int8_t value;
};
constexpr StateName kStates[] = {
    {"RUN", common::data_state_t::RUN},
    {"PAUSE", common::data_state_t::PAUSE},
    {"STOP", common::data_state_t::STOP},
    {"TERMINATE", common::data_state_t::TERMINATE},
};

bool valid_target(const std::string& s) {
  if (s == "*") return true;
  if (s.empty() || s.size() > 32) return false;
  for (const char c : s)
    if (!((c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z') || (c >= '0' && c <= '9') || c == '_' || c == '-'))
      return false;
  return true;
}

ParsedControl refuse(std::string why) { return {std::nullopt, std::move(why)}; }

// A number field within [-limit, limit]; nullopt when missing, not a number,
// not finite or outside.
std::optional<double> bounded(const json& j, const char* key, double limit) {
  const auto it = j.find(key);
  if (it == j.end() || !it->is_number()) return std::nullopt;
  const double v = it->get<double>();
  if (!std::isfinite(v) || std::fabs(v) > limit) return std::nullopt;
  return v;
}

bool confirmed(const json& j) {
  const auto it = j.find("confirmed");
  return it != j.end() && it->is_boolean() && it->get<bool>();
}

}  // namespace

ParsedControl parse_control_request(std::string_view text, const DriveLimits& limits) {
  if (text.size() > kMaxControlMessageBytes) return refuse("message too long");
  const json j = json::parse(text, nullptr, /*allow_exceptions=*/false);
  if (!j.is_object()) return refuse("not a JSON object");
  const auto type_it = j.find("type");
  if (type_it == j.end() || !type_it->is_string()) return refuse("no type");
  const std::string type = type_it->get<std::string>();
  ControlRequest r;
  if (type == "take") {
    r.kind = ControlRequest::Kind::take;
    const auto f = j.find("force");
    if (f != j.end() && !f->is_boolean()) return refuse("force: not a boolean");
    r.force = f != j.end() && f->get<bool>();
  } else if (type == "release") {
    r.kind = ControlRequest::Kind::release;
  } else if (type == "stop") {
    r.kind = ControlRequest::Kind::stop;
  } else if (type == "drive") {
    r.kind = ControlRequest::Kind::drive;
    const auto speed = bounded(j, "speed_mps", limits.max_speed_mps);
    const auto steer = bounded(j, "steering_rad", limits.max_steering_rad);
    if (!speed || !steer) return refuse("drive: speed_mps and steering_rad must be numbers within the limits");
    r.speed_mps = *speed;
    r.steering_rad = *steer;
  } else if (type == "state") {
    r.kind = ControlRequest::Kind::state;
    const auto t = j.find("target");
    const auto s = j.find("state");
    if (t == j.end() || !t->is_string() || !valid_target(t->get<std::string>()))
      return refuse("state: bad target");
    r.target = t->get<std::string>();
    bool known = false;
    if (s != j.end() && s->is_string())
      for (const auto& st : kStates)
        if (s->get<std::string>() == st.name) {
          r.state = st.value;
          known = true;
        }
    if (!known) return refuse("state: state must be RUN, PAUSE, STOP or TERMINATE");
    if (!confirmed(j)) return refuse("state: not confirmed");
  } else if (type == "power") {
    r.kind = ControlRequest::Kind::power;
    const auto a = j.find("action");
    const std::string action = a != j.end() && a->is_string() ? a->get<std::string>() : "";
    if (action == "output") {
      r.power = ControlRequest::PowerAction::output;
      const auto o = j.find("output");
      const auto on = j.find("on");
      if (o == j.end() || !o->is_number_integer() || o->get<long long>() < 0 ||
          o->get<long long>() > kMaxPowerOutput || on == j.end() || !on->is_boolean())
        return refuse("power: output 0.." + std::to_string(kMaxPowerOutput) + " and on true/false needed");
      r.output = static_cast<std::int8_t>(o->get<long long>());
      r.on = on->get<bool>();
    } else if (action == "poweroff") {
      r.power = ControlRequest::PowerAction::poweroff;
    } else if (action == "reboot") {
      r.power = ControlRequest::PowerAction::reboot;
    } else {
      return refuse("power: action must be output, poweroff or reboot");
    }
    if (!confirmed(j)) return refuse("power: not confirmed");
  } else if (type == "homing") {
    r.kind = ControlRequest::Kind::homing;
    const auto a = j.find("axis");
    if (a == j.end() || !a->is_string() || a->get<std::string>() != "steering")
      return refuse("homing: axis must be steering");
  } else {
    return refuse("unknown type");
  }
  return {r, ""};
}

std::string describe_request(const ControlRequest& r) {
  using K = ControlRequest::Kind;
  switch (r.kind) {
    case K::take: return r.force ? "take control (over another operator)" : "take control";
    case K::release: return "release control";
    // The bridge's own stops say why: an operator reading the error list
    // must tell a take-over from a page that went away.
    case K::stop: return r.cause.empty() ? "stop" : "stop by the bridge: " + r.cause;
    case K::drive: {
      char b[96];
      std::snprintf(b, sizeof b, "drive %.2f m/s steering %.3f rad", r.speed_mps, r.steering_rad);
      return b;
    }
    case K::state:
      for (const auto& st : kStates)
        if (st.value == r.state) return "state " + r.target + " " + st.name;
      return "state " + r.target;
    case K::power:
      if (r.power == ControlRequest::PowerAction::poweroff) return "power off the computer";
      if (r.power == ControlRequest::PowerAction::reboot) return "reboot the computer";
      return "power output " + std::to_string(r.output) + (r.on ? " on" : " off");
    case K::homing: return "homing steering";
  }
  return "?";
}

}  // namespace advee::web
