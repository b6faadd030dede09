// SPDX-License-Identifier: GPL-2.0
#include "advee/diagcenter/text_summary.hpp"

#include <cstdarg>
#include <cstdio>
#include <sstream>

#include "advee/diagcenter/strprintf.hpp"
#include "advee/msgs/channels.hpp"

namespace advee::diagcenter {

namespace {


template <typename Msg>
std::string age(const Latest<Msg>& l, double now, double rate_hz) {
  const double a = l.age(now);
  return strprintf(" age=%.1f", a) + (a > stale_after_s(rate_hz) ? " stale=1" : "");
}

}  // namespace

std::string token(std::string s) {
  for (auto& c : s)
    if (c == ' ' || c == '\t' || c == '=' || c == '\n') c = '_';
  return s.empty() ? "-" : s;
}

std::string text_summary(const Model& m, double now, double elapsed_s) {
  std::ostringstream o;
  o << strprintf("summary t=%.1f messages=%llu", elapsed_s,
         static_cast<unsigned long long>(m.messages()))
    << "\n";

  // Position estimate from odometry (integrated since start or the last reset).
  const auto& p = m.odometry().pose();
  o << strprintf("pose_odo x=%.3f y=%.3f heading=%.3f distance=%.3f origin=%s", p.x_m, p.y_m, p.heading_rad,
         m.odometry().distance_m(), m.odometry_from_true_pose() ? "true" : "zero");
  o << (m.odo().has() ? age(m.odo(), now, msgs::kDataOdo.rate_hz) : std::string(" age=none"))
    << "\n";

  const auto& t = m.true_pose();
  if (t.has()) {
    const double a = now - t.at;
    o << strprintf("pose_true x=%.3f y=%.3f heading=%.3f speed=%.3f steering=%.3f age=%.1f", t.x_m, t.y_m,
           t.heading_rad, t.speed_mps, t.steering_rad, a)
      << (a > stale_after_s(10) ? " stale=1" : "") << "\n";
  } else {
    o << "pose_true none\n";
  }

  if (m.odo().has())
    o << strprintf("odo v=%.3f w=%.3f", m.odo().msg.speed_mps, m.odo().msg.yaw_rate_radps)
      << age(m.odo(), now, msgs::kDataOdo.rate_hz) << "\n";
  else
    o << "odo none\n";

  // Motion: the newest command seen on the bus and what the drives do.
  o << "motion";
  if (m.motion_cmd().has())
    o << strprintf(" cmd_v=%.3f cmd_steer=%.3f cmd_age=%.1f cmd_from=", m.motion_cmd().msg.speed_mps,
           m.motion_cmd().msg.steering_rad, m.motion_cmd().age(now))
      << token(m.motion_cmd().msg.module);
  else
    o << " cmd_v=none cmd_steer=none";
  if (m.drives().has()) {
    const auto& d = m.drives().msg;
    o << strprintf(" v=%.3f steer=%.3f drives_age=%.1f", d.speed_mps, d.steering_rad, m.drives().age(now));
  } else {
    o << " v=none steer=none";
  }
  o << "\n";

  if (m.drives().has()) {
    const auto& d = m.drives().msg;
    o << "drives";
    for (std::size_t i = 0; i < static_cast<std::size_t>(d.num_drives); ++i) {
      const char* axis = d.axis[i] == lowlevel::data_drives_t::AXIS_PROPULSION ? "propulsion"
                         : d.axis[i] == lowlevel::data_drives_t::AXIS_STEERING ? "steering"
                                                                                : "axis";
      o << " " << axis << "=" << token(d.state[i]) << strprintf(" %s_fault=%d %s_homed=%d", axis,
                                                        int(d.fault[i]), axis, int(d.homed[i]));
    }
    o << strprintf(" cmd_v=%.3f cmd_steer=%.3f stopped=%d reason=", d.cmd_speed_mps, d.cmd_steering_rad,
           int(d.stopped))
      << token(d.stop_reason) << age(m.drives(), now, msgs::kDataDrives.rate_hz) << "\n";
  } else {
    o << "drives none\n";
  }

  // Modules: state (own announcement), pid, supervisor's restarts and phase.
  std::ostringstream st, pid, rs, ph, ag;
  for (const auto& [name, mi] : m.modules()) {
    st << " " << name << "="
       << (mi.state ? std::string(module::to_string(*mi.state)) : std::string("none"));
    pid << " " << name << "=" << mi.pid;
    rs << " " << name << "=";
    if (mi.restarts >= 0)
      rs << mi.restarts;
    else
      rs << "none";
    ph << " " << name << "=" << phase_name(mi.phase);
    ag << " " << name << "=";
    if (mi.state_at == kNever)
      ag << "none";
    else
      ag << strprintf("%.1f", now - mi.state_at) << (now - mi.state_at > kModuleStaleAfterS ? "!" : "");
  }
  o << "modules" << (m.modules().empty() ? " none" : st.str()) << "\n";
  o << "module_pids" << (m.modules().empty() ? " none" : pid.str()) << "\n";
  o << "module_restarts" << (m.modules().empty() ? " none" : rs.str()) << "\n";
  o << "module_phases" << (m.modules().empty() ? " none" : ph.str()) << "\n";
  o << "module_ages" << (m.modules().empty() ? " none" : ag.str()) << "\n";

  if (m.srfs().has()) {
    const auto& s = m.srfs().msg;
    o << "srf";
    for (std::size_t i = 0; i < static_cast<std::size_t>(s.num_srfs); ++i)
      o << " " << s.srf_id[i] << "=" << strprintf("%.3f", s.srf_range_m[i]);
    o << age(m.srfs(), now, msgs::kDataSrfs.rate_hz) << "\n";
    o << "ir";
    for (std::size_t i = 0; i < static_cast<std::size_t>(s.num_irs); ++i)
      o << " " << s.ir_id[i] << "=" << strprintf("%.3f", s.ir_range_m[i]);
    o << age(m.srfs(), now, msgs::kDataSrfs.rate_hz) << "\n";
  } else {
    o << "srf none\nir none\n";
  }

  if (m.beacons().has()) {
    const auto& b = m.beacons().msg;
    o << "beacons count=" << b.count;
    for (std::size_t i = 0; i < static_cast<std::size_t>(b.count); ++i)
      o << " " << b.id[i] << "=" << strprintf("%.3f", b.bearing_rad[i]);
    o << age(m.beacons(), now, msgs::kDataBeacons.rate_hz) << "\n";
  } else {
    o << "beacons none\n";
  }

  if (m.temperatures().has()) {
    const auto& tt = m.temperatures().msg;
    o << "temps";
    for (std::size_t i = 0; i < static_cast<std::size_t>(tt.count); ++i)
      o << " " << token(tt.label[i]) << "=" << strprintf("%.1f", tt.celsius[i]);
    o << age(m.temperatures(), now, msgs::kDataTemperature.rate_hz) << "\n";
  } else {
    o << "temps none\n";
  }

  if (m.fans().has()) {
    const auto& fa = m.fans().msg;
    o << "fans";
    for (std::size_t i = 0; i < static_cast<std::size_t>(fa.count); ++i)
      o << " " << token(fa.label[i]) << "=" << fa.rpm[i] << " " << token(fa.label[i])
        << "_fault=" << int(fa.fault[i]);
    o << " fan_fail=" << int(fa.fan_fail) << age(m.fans(), now, msgs::kDataFans.rate_hz) << "\n";
  } else {
    o << "fans none\n";
  }

  if (m.power().has()) {
    const auto& pw = m.power().msg;
    o << strprintf("power battery=%.2f", pw.battery_v);
    for (std::size_t i = 0; i < static_cast<std::size_t>(pw.num_outputs); ++i)
      o << " out" << i << "=" << (pw.on[i] ? "on" : "off");
    for (std::size_t i = 0; i < static_cast<std::size_t>(pw.num_outputs); ++i)
      o << " i" << i << "=" << strprintf("%.2f", pw.current_a[i]);
    o << " paused=" << int(pw.paused) << age(m.power(), now, msgs::kDataPower.rate_hz) << "\n";
  } else {
    o << "power none\n";
  }

  // PAUSE: the newest word of LL_EVENT_STOP or LL_DATA_POWER.
  if (const auto engaged = m.pause_engaged()) {
    o << "stop engaged=" << int(*engaged);
    if (m.stop_event().has())
      o << " events_source=" << (m.stop_event().msg.source == lowlevel::event_stop_t::SOURCE_PSC1 ? "psc1" : "dio")
        << strprintf(" event_age=%.1f", m.stop_event().age(now));
    o << "\n";
  } else {
    o << "stop none\n";
  }

  o << "errors total=" << m.errors_total();
  if (!m.errors().empty()) {
    const auto& e = m.errors().back();
    o << " last_module=" << token(e.msg.module) << " last_number=" << e.msg.number
      << " last_severity=" << int(e.msg.severity) << strprintf(" last_age=%.1f", now - e.at)
      << " last_text=\"" << e.msg.text << "\"";
  }
  o << "\n";
  return o.str();
}

}  // namespace advee::diagcenter
