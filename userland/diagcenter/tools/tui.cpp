// SPDX-License-Identifier: GPL-2.0
// ncurses drawing of advee-diagnostic-center. Layout for 80x24 and larger: title
// line, content, status line, help line. Everything is clipped to the
// terminal, so a smaller one shows less but never garbage; KEY_RESIZE
// redraws at the new size.
#include "tui.hpp"

#include <ncurses.h>

#include <algorithm>
#include <cmath>
#include <cstdarg>
#include <cstdio>
#include <iterator>
#include <numbers>
#include <string>
#include <vector>

#include "advee/diagcenter/sensor_layout.hpp"
#include "advee/diagcenter/strprintf.hpp"
#include "advee/msgs/channels.hpp"

namespace advee::diagcenter::tui {

namespace {

enum Pair : short { kTitle = 1, kRed, kYellow, kGreen };
constexpr double kRadToDeg = 180 / std::numbers::pi;


attr_t color(Pair p) { return has_colors() ? COLOR_PAIR(p) : A_NORMAL; }

// Text at (y, x), clipped to the screen.
void put(int y, int x, const std::string& s, attr_t a = A_NORMAL) {
  if (y < 0 || y >= LINES || x < 0 || x >= COLS) return;
  attron(a);
  mvaddnstr(y, x, s.c_str(), COLS - x);
  attroff(a);
}

// Text clipped to a column of `width`.
void put_w(int y, int x, int width, const std::string& s, attr_t a = A_NORMAL) {
  put(y, x, s.substr(0, static_cast<std::size_t>(std::max(0, width))), a);
}

int content_bottom() { return LINES - 3; }  // last row of the content area

// " (3.2 s old)" when the data is older than its channel's staleness limit.
std::string stale_mark(double age, double limit) {
  if (age <= limit) return "";
  return age > 999 ? " (old)" : strprintf(" (%.0fs old)", age);
}

template <typename Msg>
attr_t fresh_attr(const Latest<Msg>& l, double now, double rate_hz) {
  return l.age(now) > stale_after_s(rate_hz) ? A_DIM : A_NORMAL;
}

void draw_title(const Controller& ctl) {
  move(0, 0);
  clrtoeol();
  // The full name only where it leaves room for the views and the MANUAL mark.
  std::string t = COLS >= 100 ? " Advee diagnostic centre |" : " Advee |";
  put(0, 0, std::string(static_cast<std::size_t>(COLS), ' '), color(kTitle));
  put(0, 0, t, color(kTitle) | A_BOLD);
  int x = static_cast<int>(t.size());
  for (int i = 0; i < kViewCount; ++i) {
    const auto v = static_cast<View>(i);
    const std::string label = strprintf(" %d %s ", i + 1, view_name(v));
    put(0, x, label, v == ctl.view() ? A_REVERSE | A_BOLD : color(kTitle));
    x += static_cast<int>(label.size());
  }
  if (ctl.manual()) {
    const auto m = strprintf(" MANUAL %+.2f m/s %+.0f deg ", ctl.speed_mps(), ctl.steering_rad() * kRadToDeg);
    put(0, std::max(x + 1, COLS - static_cast<int>(m.size())), m, color(kRed) | A_REVERSE | A_BOLD);
  }
}

void draw_footer(const Model& model, const Controller& ctl, const char* url) {
  static const char* help[] = {
      "arrows drive  space stop  m manual on/off  h home steering  o odo=0  q quit",
      "up/down scroll  c clear  space stop  1-4/F1-F4 view  q quit",
      "up/down select  r RUN  p PAUSE  s STOP  t t TERMINATE  space stop  q quit",
      "up/down select  enter toggle  n on  f off  space stop  1-4 view  q quit",
  };
  std::string status = ctl.status();
  if (model.messages() == 0)
    status = strprintf("no LCM message yet on %s", url);
  move(LINES - 2, 0);
  clrtoeol();
  put(LINES - 2, 0, status, A_BOLD);
  move(LINES - 1, 0);
  clrtoeol();
  put(LINES - 1, 0, help[static_cast<int>(ctl.view())], A_REVERSE);
}

// --- summary ---------------------------------------------------------------

// The ranges around the robot outline, in the box at (top, left) of h x w.
void draw_ranges(const Model& model, double now, int top, int left, int h, int w) {
  if (h < 9 || w < 24) return;
  const auto& s = model.srfs();
  std::string title = "Ranges (m)";
  if (s.has()) title += stale_mark(s.age(now), stale_after_s(msgs::kDataSrfs.rate_hz));
  else title += ": no LL_DATA_SRFS yet";
  put_w(top, left, w, title, A_BOLD);
  const int ctop = top + 1, ch = h - 2;  // canvas rows; the last row lists IR ranges
  const Outline o;
  const double cy = ctop + ch / 2.0, cx = left + w / 2.0;
  const double sy = 6.0, sx = 12.0;  // rows and columns per metre (cells are ~2:1)
  const double xmid = (o.front_m + o.rear_m) / 2;
  auto row_of = [&](double x) { return cy - (x - xmid) * sy; };
  auto col_of = [&](double y) { return cx - y * sx; };
  // Occupancy, so that labels do not overwrite the outline or each other.
  std::vector<std::string> grid(static_cast<std::size_t>(LINES), std::string(static_cast<std::size_t>(COLS), ' '));
  auto mark = [&](int r, int c, int n) {
    for (int i = 0; i < n; ++i)
      if (r >= 0 && r < LINES && c + i >= 0 && c + i < COLS) grid[static_cast<std::size_t>(r)][static_cast<std::size_t>(c + i)] = '#';
  };
  auto free_at = [&](int r, int c, int n) {
    if (r < ctop || r >= ctop + ch || c < left || c + n > left + w) return false;
    for (int i = 0; i < n; ++i)
      if (grid[static_cast<std::size_t>(r)][static_cast<std::size_t>(c + i)] != ' ') return false;
    return true;
  };
  const int r0 = static_cast<int>(std::lround(row_of(o.front_m)));
  const int r1 = static_cast<int>(std::lround(row_of(o.rear_m)));
  const int c0 = static_cast<int>(std::lround(col_of(o.half_width_m)));
  const int c1 = static_cast<int>(std::lround(col_of(-o.half_width_m)));
  for (int r = r0; r <= r1; ++r) {
    const bool edge = r == r0 || r == r1;
    std::string line(static_cast<std::size_t>(c1 - c0 + 1), edge ? '-' : ' ');
    line.front() = line.back() = edge ? '+' : '|';
    put(r, c0, line);
    mark(r, c0, c1 - c0 + 1);
  }
  put(r0 + 1, (c0 + c1) / 2, "^", A_BOLD);
  put((r0 + r1) / 2, (c0 + c1) / 2 - 2, "ROBOT", A_DIM);

  if (!s.has()) return;
  const attr_t stale = fresh_attr(s, now, msgs::kDataSrfs.rate_hz);
  const auto layout = default_srf_layout();
  std::string others;
  for (std::size_t i = 0; i < static_cast<std::size_t>(s.msg.num_srfs); ++i) {
    const int id = s.msg.srf_id[i];
    const float range = s.msg.srf_range_m[i];
    const std::string label = range < 0 ? "--" : strprintf("%.2f", range);
    const auto it = std::find_if(layout.begin(), layout.end(), [&](const SensorPlace& p) { return p.id == id; });
    if (it == layout.end()) {
      others += strprintf(" %d=%s", id, label.c_str());
      continue;
    }
    const double hd = it->heading_deg / kRadToDeg;
    const double dr = -std::cos(hd), dc = -std::sin(hd) * 2;
    const int n = static_cast<int>(label.size());
    // From the sensor outwards along its beam until there is room.
    for (double k = 1.5; k < 12; k += 0.5) {
      const int r = static_cast<int>(std::lround(row_of(it->x_m) + dr * k));
      const int c = static_cast<int>(std::lround(col_of(it->y_m) + dc * k - n / 2.0));
      if (free_at(r, c, n)) {
        attr_t a = stale;
        if (range >= 0 && range < 0.3) a |= color(kRed) | A_BOLD;
        else if (range >= 0 && range < 0.7) a |= color(kYellow);
        put(r, c, label, a);
        mark(r, c - 1, n + 2);  // a blank between neighbours
        break;
      }
    }
  }
  std::string ir = "IR";
  for (std::size_t i = 0; i < static_cast<std::size_t>(s.msg.num_irs); ++i)
    ir += s.msg.ir_range_m[i] < 0 ? strprintf(" %d:--", s.msg.ir_id[i])
                                  : strprintf(" %d:%.2f", s.msg.ir_id[i], s.msg.ir_range_m[i]);
  if (!others.empty()) ir += "  SRF" + others;
  put_w(top + h - 1, left, w, ir, stale);
}

void draw_modules_brief(const Model& model, double now, int top, int width, int max_rows) {
  put_w(top, 0, width, "Module          state  pid     rst age", A_BOLD);
  int r = top + 1;
  int shown = 0;
  for (const auto& [name, mi] : model.modules()) {
    if (shown == max_rows) {
      put_w(r, 0, width, strprintf("  ... %zu more (view 3)", model.modules().size() - static_cast<std::size_t>(shown)), A_DIM);
      break;
    }
    const double age = now - mi.state_at;
    const bool stale = mi.state_at == kNever || age > kModuleStaleAfterS;
    const std::string st = mi.state ? std::string(module::to_string(*mi.state)) : "-";
    const std::string rst = mi.restarts >= 0 ? std::to_string(mi.restarts) : "-";
    const std::string ag = mi.state_at == kNever ? "-" : strprintf("%.0fs", age);
    attr_t a = stale ? A_DIM : A_NORMAL;
    if (mi.state == module::State::Run && !stale) a |= color(kGreen);
    else if (mi.state == module::State::Error || mi.phase == 4 || mi.phase == 0) a |= color(kRed);
    put_w(r, 0, width, strprintf("%-15.15s %-6.6s %-7d %-3s %s", name.c_str(), st.c_str(), mi.pid, rst.c_str(), ag.c_str()), a);
    ++r;
    ++shown;
  }
  if (model.modules().empty()) put_w(r, 0, width, "  (no CM_DATA_STATE yet)", A_DIM);
}

// CiA 402 state names, short enough for the summary's column.
std::string short_state(const std::string& s) {
  if (s == "operation enabled") return "enabled";
  if (s == "switch on disabled") return "sw-on-disabled";
  if (s == "ready to switch on") return "ready";
  if (s == "quick stop active") return "quick-stop";
  if (s == "fault reaction active") return "fault-reaction";
  return s;
}

void draw_summary(const Model& model, double now) {
  // Left column 39 wide, a blank, the ranges from column 41.
  const int w = COLS >= 80 ? 39 : COLS;
  const int bottom = content_bottom();
  if (LINES < 24 || COLS < 40) {
    // The fixed rows and the module list would overlap: say so instead.
    put(1, 0, strprintf("the summary needs 40x24 or more (now %dx%d); 80x24 adds the ranges", COLS, LINES), A_BOLD);
    return;
  }
  // Rows for the module list: what is left above the 12 fixed rows.
  const int fixed = 12;
  const int list_rows = std::max(1, bottom - fixed - 1 - 1);
  draw_modules_brief(model, now, 1, w, list_rows);
  int r = bottom - fixed + 1;

  const auto& p = model.odometry().pose();
  const auto& odo = model.odo();
  put_w(r++, 0, w,
        strprintf("Pos odo  x %+6.2f y %+6.2f h %+6.1f", p.x_m, p.y_m, p.heading_rad * kRadToDeg) +
            (odo.has() ? stale_mark(odo.age(now), stale_after_s(msgs::kDataOdo.rate_hz)) : " -"),
        odo.has() ? fresh_attr(odo, now, msgs::kDataOdo.rate_hz) : A_DIM);
  const auto& t = model.true_pose();
  if (t.has())
    put_w(r++, 0, w, strprintf("Pos true x %+6.2f y %+6.2f h %+6.1f", t.x_m, t.y_m, t.heading_rad * kRadToDeg) +
                         stale_mark(now - t.at, stale_after_s(10)));
  else
    put_w(r++, 0, w, "Pos true (no SIM_DATA_POSE)", A_DIM);

  const auto& c = model.motion_cmd();
  if (c.has())
    put_w(r++, 0, w, strprintf("Command  v %+5.2f m/s steer %+5.1f by %s", c.msg.speed_mps, c.msg.steering_rad * kRadToDeg,
                       c.msg.module == "diagnostic_center" ? "us" : c.msg.module.c_str()) +
                         stale_mark(c.age(now), 1.0),
          c.age(now) > 1.0 ? A_DIM : A_NORMAL);
  else
    put_w(r++, 0, w, "Command  (no LL_CMD_MOTION)", A_DIM);

  const auto& d = model.drives();
  if (d.has()) {
    const attr_t a = fresh_attr(d, now, msgs::kDataDrives.rate_hz);
    put_w(r++, 0, w, strprintf("Drives   v %+5.2f m/s steer %+5.1f", d.msg.speed_mps, d.msg.steering_rad * kRadToDeg) +
                         stale_mark(d.age(now), stale_after_s(msgs::kDataDrives.rate_hz)), a);
    std::string states;
    for (std::size_t i = 0; i < static_cast<std::size_t>(d.msg.num_drives); ++i)
      states += (d.msg.axis[i] == lowlevel::data_drives_t::AXIS_PROPULSION ? "EPOS " : "IclA ") + short_state(d.msg.state[i]) +
                (d.msg.homed[i] ? " H" : "") + (d.msg.fault[i] ? strprintf(" F%04X", static_cast<unsigned>(d.msg.error_code[i])) : "") + "  ";
    put_w(r++, 0, w, " " + states, a | (d.msg.stopped ? color(kRed) : A_NORMAL));
    if (d.msg.stopped)
      put_w(r++, 0, w, "QUICK STOP: " + d.msg.stop_reason, color(kRed) | A_BOLD);
    else
      put_w(r++, 0, w, "Motion enabled", a);
  } else {
    put_w(r++, 0, w, "Drives   (no LL_DATA_DRIVES)", A_DIM);
    r += 2;
  }

  const auto pause = model.pause_engaged();
  if (!pause)
    put_w(r++, 0, w, "PAUSE    (no LL_DATA_POWER)", A_DIM);
  else if (*pause)
    put_w(r++, 0, w, "PAUSE    ENGAGED", color(kRed) | A_REVERSE | A_BOLD);
  else
    put_w(r++, 0, w, "PAUSE    released");

  const auto& tt = model.temperatures();
  if (tt.has()) {
    std::string s = "Temp    ";
    for (std::size_t i = 0; i < static_cast<std::size_t>(tt.msg.count); ++i)
      s += strprintf(" %s %.1f", tt.msg.label[i].c_str(), tt.msg.celsius[i]);
    put_w(r++, 0, w, s + " C" + stale_mark(tt.age(now), stale_after_s(msgs::kDataTemperature.rate_hz)),
          fresh_attr(tt, now, msgs::kDataTemperature.rate_hz));
  } else {
    put_w(r++, 0, w, "Temp     (no LL_DATA_TEMPERATURE)", A_DIM);
  }
  const auto& fa = model.fans();
  if (fa.has()) {
    std::string s = "Fans    ";
    bool bad = fa.msg.fan_fail;
    for (std::size_t i = 0; i < static_cast<std::size_t>(fa.msg.count); ++i) {
      s += strprintf(" %s %d", fa.msg.label[i].c_str(), fa.msg.rpm[i]) + (fa.msg.fault[i] ? "!" : "");
      bad = bad || fa.msg.fault[i];
    }
    s += fa.msg.fan_fail ? " FAN-FAIL" : "";
    put_w(r++, 0, w, s + stale_mark(fa.age(now), stale_after_s(msgs::kDataFans.rate_hz)),
          fresh_attr(fa, now, msgs::kDataFans.rate_hz) | (bad ? color(kRed) : A_NORMAL));
  } else {
    put_w(r++, 0, w, "Fans     (no LL_DATA_FANS)", A_DIM);
  }
  const auto& pw = model.power();
  if (pw.has()) {
    std::string s = "Power   ";
    for (std::size_t i = 0; i < static_cast<std::size_t>(pw.msg.num_outputs); ++i)
      s += strprintf(" %zu%c", i, pw.msg.on[i] ? '+' : '-');
    put_w(r++, 0, w, s + stale_mark(pw.age(now), stale_after_s(msgs::kDataPower.rate_hz)),
          fresh_attr(pw, now, msgs::kDataPower.rate_hz));
  } else {
    put_w(r++, 0, w, "Power    (no LL_DATA_POWER)", A_DIM);
  }
  const auto& b = model.beacons();
  if (b.has()) {
    std::string s = "Beacons ";
    for (std::size_t i = 0; i < static_cast<std::size_t>(b.msg.count); ++i)
      s += strprintf(" %d@%.0f", b.msg.id[i], b.msg.bearing_rad[i] * kRadToDeg);
    if (b.msg.count == 0) s += " none seen";
    put_w(r++, 0, w, s + stale_mark(b.age(now), stale_after_s(msgs::kDataBeacons.rate_hz)),
          fresh_attr(b, now, msgs::kDataBeacons.rate_hz));
  } else {
    put_w(r++, 0, w, "Beacons  (no LL_DATA_BEACONS)", A_DIM);
  }
  if (model.errors().empty())
    put_w(r++, 0, w, strprintf("Errors   %llu", static_cast<unsigned long long>(model.errors_total())));
  else
    put_w(r++, 0, w, strprintf("Errors   %llu, last %s: %s", static_cast<unsigned long long>(model.errors_total()),
                       model.errors().back().msg.module.c_str(), model.errors().back().msg.text.c_str()),
          model.errors().back().msg.severity >= common::error_t::SEVERITY_ERROR ? color(kRed) : color(kYellow));

  if (COLS >= 80) draw_ranges(model, now, 1, w + 2, bottom, COLS - w - 2);
}

// --- errors ----------------------------------------------------------------

void draw_errors(const Model& model, const Controller& ctl, double now) {
  put(1, 0, strprintf("Errors: %zu kept, %llu since start (CM_DATA_ERROR)", model.errors().size(),
              static_cast<unsigned long long>(model.errors_total())), A_BOLD);
  put(2, 0, "   age module          sev     num  text", A_BOLD);
  const int first_row = 3, rows = content_bottom() - first_row + 1;
  if (rows <= 0) return;
  const auto& errs = model.errors();
  // The newest at the bottom; scrolling shows older ones.
  const long end = static_cast<long>(errs.size()) - static_cast<long>(ctl.error_scroll());
  const long begin = std::max(0L, end - rows);
  int r = first_row;
  for (long i = begin; i < end; ++i) {
    const auto& e = errs[static_cast<std::size_t>(i)];
    static const char* sev[] = {"notice", "warning", "ERROR"};
    const int s = std::clamp<int>(e.msg.severity, 0, 2);
    attr_t a = s == 2 ? color(kRed) : s == 1 ? color(kYellow) : A_NORMAL;
    if (e.msg.fatal) a |= A_BOLD;
    put(r++, 0, strprintf("%5.0fs %-15.15s %-7s %4d  %s%s", now - e.at, e.msg.module.c_str(), sev[s], e.msg.number,
                  e.msg.fatal ? "FATAL " : "", e.msg.text.c_str()), a);
  }
  if (errs.empty()) put(first_row, 0, "  (none)", A_DIM);
}

// --- modules ---------------------------------------------------------------

void draw_modules(const Model& model, const Controller& ctl, double now) {
  put(1, 0, "Modules: CM_DATA_STATE; supervisor phase and restarts: CM_DATA_MODULES", A_BOLD);
  put(2, 0, "  module           state     pid        age  supervisor   restarts exit next", A_BOLD);
  int r = 3;
  std::size_t i = 0;
  const std::size_t sel = ctl.module_row();
  const int rows = content_bottom() - r + 1;
  // Keep the selection visible when the list is longer than the screen.
  const std::size_t skip = rows > 0 && sel >= static_cast<std::size_t>(rows) ? sel - static_cast<std::size_t>(rows) + 1 : 0;
  for (const auto& [name, mi] : model.modules()) {
    if (i < skip) {
      ++i;
      continue;
    }
    if (r > content_bottom()) break;
    const bool stale = mi.state_at == kNever || now - mi.state_at > kModuleStaleAfterS;
    const std::string st = mi.state ? std::string(module::to_string(*mi.state)) : "-";
    const std::string ag = mi.state_at == kNever ? "-" : strprintf("%.1fs", now - mi.state_at);
    const std::string rst = mi.restarts >= 0 ? std::to_string(mi.restarts) : "-";
    const std::string ex = mi.exit_status >= 0 ? std::to_string(mi.exit_status) : "-";
    const std::string nx = mi.next_start_ms >= 0 ? strprintf("%dms", mi.next_start_ms) : "-";
    attr_t a = stale ? A_DIM : A_NORMAL;
    if (i == sel) a = A_REVERSE;
    put(r++, 0, strprintf("%c %-16.16s %-9.9s %-8d %6s  %-12s %-8s %-4s %s", i == sel ? '>' : ' ', name.c_str(), st.c_str(),
                  mi.pid, ag.c_str(), phase_name(mi.phase), rst.c_str(), ex.c_str(), nx.c_str()), a);
    ++i;
  }
  if (model.modules().empty()) put(3, 0, "  (no module announced itself yet)", A_DIM);
}

// --- power -----------------------------------------------------------------

void draw_power(const Model& model, const Controller& ctl, double now) {
  const auto& pw = model.power();
  std::string head = "Power outputs (PSC1): LL_CMD_POWER";
  if (pw.has()) {
    head += pw.msg.battery_v >= 0 ? strprintf(", battery %.2f V", pw.msg.battery_v) : ", battery not measured";
    head += stale_mark(pw.age(now), stale_after_s(msgs::kDataPower.rate_hz));
  } else {
    head += ", no LL_DATA_POWER yet";
  }
  put(1, 0, head, A_BOLD);
  const auto pause = model.pause_engaged();
  put(2, 0, !pause ? "PAUSE unknown" : *pause ? "PAUSE ENGAGED" : "PAUSE released",
      pause && *pause ? color(kRed) | A_REVERSE : A_NORMAL);
  put(3, 0, "  output  state  current", A_BOLD);
  int r = 4;
  for (int i = 0; i < ctl.power_outputs() && r <= content_bottom(); ++i, ++r) {
    const auto ui = static_cast<std::size_t>(i);
    const bool known = pw.has() && i < pw.msg.num_outputs;
    const std::string st = known ? (pw.msg.on[ui] ? "ON" : "off") : "?";
    const std::string cur = known && pw.msg.current_a[ui] >= 0 ? strprintf("%.2f A", pw.msg.current_a[ui]) : "-";
    attr_t a = known && pw.msg.on[ui] ? color(kGreen) : A_NORMAL;
    if (i == ctl.power_row()) a = A_REVERSE;
    put(r, 0, strprintf("%c %-7d %-6s %s", i == ctl.power_row() ? '>' : ' ', i, st.c_str(), cur.c_str()), a);
  }
  const auto& pc = model.power_cmd();
  if (pc.has() && r + 1 <= content_bottom())
    put(r + 1, 0, strprintf("last LL_CMD_POWER: output %d %s from %s, %.1f s ago", pc.msg.output, pc.msg.on ? "on" : "off",
                    pc.msg.module.c_str(), pc.age(now)), A_DIM);
}

}  // namespace

Screen::Screen() {
  initscr();
  cbreak();
  noecho();
  keypad(stdscr, TRUE);
  nodelay(stdscr, TRUE);
  curs_set(0);
  if (has_colors()) {
    start_color();
    use_default_colors();
    init_pair(kTitle, COLOR_BLACK, COLOR_CYAN);
    init_pair(kRed, COLOR_RED, -1);
    init_pair(kYellow, COLOR_YELLOW, -1);
    init_pair(kGreen, COLOR_GREEN, -1);
  }
}

Screen::~Screen() { endwin(); }

Key Screen::read_key() {
  const int c = getch();
  switch (c) {
    case ERR: return {Key::None};
    case KEY_UP: return {Key::Up};
    case KEY_DOWN: return {Key::Down};
    case KEY_LEFT: return {Key::Left};
    case KEY_RIGHT: return {Key::Right};
    case KEY_ENTER:
    case '\n':
    case '\r': return {Key::Enter};
    case KEY_RESIZE: return {Key::Resize};
    default: break;
  }
  for (int n = 1; n <= 12; ++n)
    if (c == KEY_F(n)) return Key::fn(n);
  if (c >= 0 && c < 128) return Key::ch(c);
  return {Key::Char, 0};  // a key we have no use for
}

void draw(const Model& model, const Controller& ctl, double now, const char* url) {
  erase();
  draw_title(ctl);
  switch (ctl.view()) {
    case View::Summary: draw_summary(model, now); break;
    case View::Errors: draw_errors(model, ctl, now); break;
    case View::Modules: draw_modules(model, ctl, now); break;
    case View::Power: draw_power(model, ctl, now); break;
  }
  draw_footer(model, ctl, url);
  refresh();
}

}  // namespace advee::diagcenter::tui
