// SPDX-License-Identifier: GPL-2.0
// rs485-stack-test: the rs485 library's drivers against advee-rs485-sim over the
// real stack (simulated FPGA -> ts-uart -> n_rs485 -> library), TAP output.
// Run by tests/vm/rs485/drivers.sh with tests/vm/rs485/stack.yaml, whose
// devices and firmware versions this program expects.
#include <cmath>
#include <condition_variable>
#include <cstdio>
#include <future>
#include <mutex>
#include <numbers>
#include <regex>
#include <string>
#include <thread>

#include "advee/rs485/bus.hpp"
#include "advee/rs485/devices/psc1.hpp"
#include "advee/rs485/devices/sbs1.hpp"
#include "advee/rs485/devices/sd1.hpp"
#include "advee/rs485/devices/so1.hpp"
#include "advee/rs485sim/control_client.hpp"
#include "tap.hpp"

namespace rs = advee::rs485;
using advee::rs485sim::control_ok;
using advee::rs485sim::vmtest::Tap;
using namespace std::chrono_literals;
using Clock = std::chrono::steady_clock;

namespace {

std::string g_ctl;

void sim(const std::string& cmd) { control_ok(g_ctl, cmd); }

// One counter of "stats DEV" (e.g. "resends").
unsigned long sim_stat(const std::string& dev, const std::string& name) {
  const auto reply = control_ok(g_ctl, "stats " + dev);
  std::smatch m;
  const std::regex re("(^| )" + std::regex_replace(name, std::regex(R"([\[\]])"), R"(\$&)") + "=([0-9]+)");
  return std::regex_search(reply, m, re) ? std::stoul(m[2]) : 0;
}

bool near(std::optional<double> got, double want, double tol) { return got && std::fabs(*got - want) <= tol; }

std::string describe(const std::error_code& ec) { return ec ? ec.message() : "OK"; }

double ms_since(Clock::time_point t) { return std::chrono::duration<double, std::milli>(Clock::now() - t).count(); }

}  // namespace

int main(int argc, char** argv) {
  if (argc != 6) {
    std::fprintf(stderr, "usage: rs485-stack-test CONTROL_SOCKET BUS_A BUS_B POWER TIMEOUT_MS\n");
    return 2;
  }
  g_ctl = argv[1];
  const auto timeout = std::chrono::milliseconds(std::stoi(argv[5]));
  Tap tap(32);
  try {
    rs::BusOptions opt;
    opt.config = rs::BusConfig{};
    opt.config->timeout = timeout;
    opt.config->retries = 2;
    rs::Bus a(argv[2], opt), b(argv[3], opt), power(argv[4], opt);
    rs::Sd1 sd1(a, 0x10), sd1b(a, 0x11);
    rs::So1 so1(a, 0x20);
    rs::Sbs1 sbs1(b, 0x30);
    rs::Psc1 psc1(power, 0x01);

    // --- firmware versions (stack.yaml) ---
    const std::pair<rs::Device*, rs::FirmwareVersion> fw[] = {
        {&sd1, {1, 2}}, {&sd1b, {1, 3}}, {&so1, {2, 0}}, {&sbs1, {3, 1}}, {&psc1, {4, 0}}};
    for (const auto& [dev, want] : fw) {
      const auto v = dev->firmware_version();
      char desc[64];
      std::snprintf(desc, sizeof(desc), "firmware version of node 0x%02x is %u.%u", dev->address(), want.major,
                    want.minor);
      if (!v) tap.diag("error: %s", describe(v.error()).c_str());
      tap.ok(v && *v == want, desc);
    }

    // --- SD1 readings in metres ---
    sim("set a:sd1@0x10 srf all 2.0");
    sim("set a:sd1@0x10 srf 3 1.25");
    sim("set a:sd1@0x10 srf 0 0");
    sim("set a:sd1@0x10 srf 7 none");
    sim("set a:sd1@0x10 ir 0 0.1");
    sim("set a:sd1@0x10 ir 1 none");
    sim("set a:sd1@0x11 srf all 0.42");
    {
      const auto d = sd1.distances();
      bool good = d && d->srf_m.size() == 8 && d->ir_m.size() == 2;
      if (good) {
        good = near(d->srf_m[3], 1.25, 0.005) && near(d->srf_m[0], 0.0, 0.005) && near(d->srf_m[5], 2.0, 0.005) &&
               !d->srf_m[7] && near(d->ir_m[0], 0.1, 0.0011) && !d->ir_m[1];
      } else {
        tap.diag("distances: %s", describe(d.error()).c_str());
      }
      tap.ok(good, "sd1@0x10 GET_BOTH: srf 1.25 m, 0 m, 2 m, no echo; ir 0.1 m, out of range");
      const auto e = sd1b.srf();
      bool all = e && e->size() == 8;
      for (std::size_t i = 0; all && i < 8; ++i) all = near((*e)[i], 0.42, 0.005);
      tap.ok(all, "sd1@0x11 on the same bus reports its own readings (0.42 m)");
      const auto ir = sd1.ir();
      tap.ok(ir && ir->size() == 2 && near((*ir)[0], 0.1, 0.0011) && !(*ir)[1], "sd1@0x10 GET_IR alone");
    }
    sim("set a:sd1@0x10 pause 0x05");
    {
      const auto p = sd1.pause_sources();
      const auto ec = sd1.clear_pause_sources();
      const auto q = sd1.pause_sources();
      tap.ok(p && p->front_bumper() && p->ground_sensor() && !p->rear_bumper() && !ec && q && !q->any(),
             "sd1 PAUSE sources: front bumper + ground sensor, then cleared");
    }

    // --- SO1 ticks, widths and wrap-around ---
    sim("set a:so1@0x20 ticks 130 -2");
    {
      const auto w1 = so1.raw_ticks(1), w2 = so1.raw_ticks(2);
      tap.ok(w1 && w1->left == -126 && w1->right == -2, "so1 width 1: 130 ticks wrap to -126, -2 stays -2");
      tap.ok(w2 && w2->left == 130 && w2->right == -2, "so1 width 2: 130, -2");
    }
    sim("set a:so1@0x20 ticks 4294967301 -40000");
    {
      const auto w4 = so1.raw_ticks(4);
      tap.ok(w4 && w4->left == 5 && w4->right == -40000, "so1 width 4: 2^32+5 wraps to 5, -40000");
    }
    {
      bool good = !so1.reset_ticks();
      rs::So1Counts c;
      for (long t : {100L, 200L, 300L, 250L}) {  // steps < 128: the accumulator follows the wrap
        sim("set a:so1@0x20 ticks " + std::to_string(t) + " " + std::to_string(-t));
        const auto r = so1.counts(1);
        good = good && r.has_value();
        if (r) c = *r;
      }
      tap.diag("accumulated %lld %lld", static_cast<long long>(c.left), static_cast<long long>(c.right));
      tap.ok(good && c.left == 250 && c.right == -250, "so1 width-1 readings accumulate across the wrap to 250, -250");
    }
    {
      const auto r = a.transact(rs::Request(0x20, rs::so1::instr::kGetTicks, {3}));
      tap.ok(r.error == rs::Outcome::device_error, "so1 GET_TICKS width 3: DEVERR (" + describe(r.error) + ")");
    }

    // --- SBS1 bearings in radians ---
    sim("set b:sbs1@0x30 beacon 1 90 200");
    sim("set b:sbs1@0x30 beacon 2 359.5 17");
    sim("set b:sbs1@0x30 beacon 3 10 50");
    {
      const std::uint8_t ids[] = {1, 2};
      const auto ec = sbs1.set_beacon_ids(ids);
      const auto bs = sbs1.beacons();
      bool good = !ec && bs && bs->size() == 2;
      if (good) {
        const auto& x = (*bs)[0];
        const auto& y = (*bs)[1];
        good = x.id == 1 && std::fabs(x.bearing_rad - std::numbers::pi / 2) < 1e-3 && x.quality == 200 && y.id == 2 &&
               std::fabs(y.bearing_rad - 359.5 * std::numbers::pi / 180) < 1e-3 && y.quality == 17;
      }
      tap.ok(good, "sbs1: ids {1,2} set, bearings 90 and 359.5 degrees in radians with quality (beacon 3 not asked)");
    }

    // --- PSC1 channels and currents ---
    {
      const auto s = psc1.set_power_status(0x30, 0x10);
      const auto g = psc1.power_status();
      tap.ok(s && *s == 0x1f && g && *g == 0x1f, "psc1 SET_PWR_STATUS mask 0x30 values 0x10 on 0x0f -> 0x1f");
    }
    sim("set power:psc1@0x01 current all 0.5");
    sim("set power:psc1@0x01 current 0 1.25");
    sim("set power:psc1@0x01 current 7 none");
    {
      const auto c = psc1.currents();
      tap.ok(c && near((*c)[0], 1.25, 0.001) && near((*c)[4], 0.5, 0.001) && near((*c)[5], 0.0, 0.001) && !(*c)[7],
             "psc1 currents: 1.25 A, 0.5 A, 0 A (channel off), no sensor");
    }

    // --- timeouts: no answer ---
    {
      a.reset_node(0x11);
      sim("fault a:sd1@0x11 no-answer 1");
      const auto t0 = Clock::now();
      const auto r = a.transact(rs::Request(0x11, rs::sd1::instr::kGetBoth));
      const double ms = ms_since(t0);
      tap.diag("no answer: %s after %u attempts in %.0f ms", describe(r.error).c_str(), r.attempts, ms);
      tap.ok(r.error == rs::Outcome::timeout && r.attempts == 3, "no answer: TIMEOUT after 1 + 2 retries");
      tap.ok(ms >= 3 * double(timeout.count()) * 0.95, "no answer: the call waited 3 response timeouts");
      const auto n = a.node(0x11);
      tap.ok(n.errors == 8, "no answer: node 0x11 error counter +8 (" + std::to_string(n.errors) + ")");
      sim("fault a:sd1@0x11 clear");
      const auto ok = sd1b.srf();
      tap.ok(ok.has_value() && a.node(0x11).errors == 7, "node answers again once the fault is cleared");
    }

    // --- corrupted CRC: RESEND, executed once ---
    {
      sim("reset-stats a:so1@0x20");
      sim("fault a:so1@0x20 bad-crc once");
      const auto r = a.transact(rs::Request(0x20, rs::so1::instr::kResetTicks));
      tap.diag("bad CRC once: %s after %u attempts", describe(r.error).c_str(), r.attempts);
      tap.ok(r.ok() && r.attempts == 2, "bad CRC once: OK on the second attempt");
      const auto resends = sim_stat("a:so1@0x20", "resends");
      const auto execs = sim_stat("a:so1@0x20", "exec[0x02]");
      tap.ok(resends == 1 && execs == 1,
             "bad CRC once: the retry was a RESEND, RESET_TICKS executed once (resends=" + std::to_string(resends) +
                 " executed=" + std::to_string(execs) + ")");
      sim("reset-stats a:so1@0x20");
      sim("fault a:so1@0x20 bad-crc 1");
      const auto bad = a.transact(rs::Request(0x20, rs::so1::instr::kResetTicks));
      sim("fault a:so1@0x20 clear");
      tap.ok(bad.error == rs::Outcome::bad_crc && bad.attempts == 3 && sim_stat("a:so1@0x20", "exec[0x02]") == 1 &&
                 sim_stat("a:so1@0x20", "resends") == 2,
             "bad CRC always: BADCRC after 3 attempts, executed once, 2 RESENDs (" + describe(bad.error) + ")");
    }

    // --- UNKINSTR ---
    {
      const auto r = a.transact(rs::Request(0x10, 0x77));
      tap.ok(r.error == rs::Outcome::unknown_instruction && r.attempts == 1,
             "instruction 0x77 unknown to sd1: UNKINSTR, not retried (" + describe(r.error) + ")");
      sim("fault b:sbs1@0x30 unkinstr once");
      const auto bs = sbs1.beacons();
      tap.ok(!bs && bs.error() == rs::Outcome::unknown_instruction, "injected UNKINSTR reaches the driver");
    }

    // --- slow answer ---
    {
      sim("fault a:sd1@0x10 slow-ms " + std::to_string(2 * timeout.count() + 50));
      sim("fault a:sd1@0x10 slow once");
      const auto r = a.transact(rs::Request(0x10, rs::sd1::instr::kGetSrf));
      tap.diag("slow once: %s after %u attempts", describe(r.error).c_str(), r.attempts);
      tap.ok(r.ok() && r.attempts == 2 && r.data.size() == 17, "answer later than the timeout: retried, OK");
      std::this_thread::sleep_for(2 * timeout + 100ms);  // let the late answer pass
    }

    // --- PSC1 events, also while a transaction with the node is pending ---
    {
      std::mutex m;
      std::condition_variable cv;
      std::vector<std::pair<rs::PauseEvent, Clock::time_point>> pauses;
      std::vector<rs::PowerEvent> powers;
      auto s1 = psc1.on_pause([&](const rs::PauseEvent& e) {
        std::lock_guard l(m);
        pauses.emplace_back(e, Clock::now());
        cv.notify_all();
      });
      auto s2 = psc1.on_power([&](const rs::PowerEvent& e) {
        std::lock_guard l(m);
        powers.push_back(e);
        cv.notify_all();
      });
      sim("event power:psc1@0x01 pause 0 0");
      {
        std::unique_lock l(m);
        cv.wait_for(l, 2s, [&] { return !pauses.empty(); });
        tap.ok(pauses.size() == 1 && !pauses[0].first.engaged, "psc1 PAUSE event (released) delivered");
        pauses.clear();
      }
      // The answer to GET_CURRENTS comes 600 ms late; the event is sent 150 ms into the wait.
      sim("fault power:psc1@0x01 slow-ms 600");
      sim("fault power:psc1@0x01 slow once");
      const auto t0 = Clock::now();
      auto pending = std::async(std::launch::async, [&] {
        const auto r = psc1.currents(rs::CallOptions(std::chrono::microseconds(2s), 0u));
        return std::make_pair(r, Clock::now());
      });
      std::this_thread::sleep_for(150ms);
      sim("event power:psc1@0x01 pause 1 0x03");
      const auto [cur, t_end] = pending.get();
      std::unique_lock l(m);
      cv.wait_for(l, 2s, [&] { return !pauses.empty(); });
      const bool got = pauses.size() == 1 && pauses[0].first.engaged && pauses[0].first.sources == 0x03;
      tap.diag("call took %.0f ms, event after %.0f ms", std::chrono::duration<double, std::milli>(t_end - t0).count(),
               got ? std::chrono::duration<double, std::milli>(pauses[0].second - t0).count() : -1.0);
      tap.ok(got && pauses[0].second < t_end, "PAUSE event delivered while GET_CURRENTS to the same node was pending");
      tap.ok(cur.has_value() && near((*cur)[0], 1.25, 0.001),
             "the pending transaction got its own response, not the event (" + describe(cur.error()) + ")");
      l.unlock();
      sim("set power:psc1@0x01 status 0x00");
      const auto ec = psc1.reset();
      l.lock();
      cv.wait_for(l, 2s, [&] { return !powers.empty(); });
      tap.ok(!ec && powers.size() == 1 && powers[0].status == 0x0f,
             "psc1 RESET: ACK, then a POWER event with the boot status 0x0f");
    }

    // --- broadcast RESET ---
    {
      for (const char* d : {"a:sd1@0x10", "a:sd1@0x11", "a:so1@0x20"}) sim(std::string("reset-stats ") + d);
      sim("set a:so1@0x20 ticks 77 77");
      const auto ec = rs::broadcast_reset(a);
      std::this_thread::sleep_for(timeout);  // the frame leaves after the call returns
      const bool all = sim_stat("a:sd1@0x10", "broadcasts") == 1 && sim_stat("a:sd1@0x11", "broadcasts") == 1 &&
                       sim_stat("a:so1@0x20", "broadcasts") == 1;
      const auto t = so1.raw_ticks(2);
      tap.ok(!ec && all && t && t->left == 0 && t->right == 0,
             "broadcast RESET reaches every node of the bus, none answers, so1 counts from 0");
    }
    const auto st = a.stats();
    tap.diag("bus a: xfers %llu ok %llu failed %llu timeouts %llu retries %llu crc %llu unexpected %llu",
             static_cast<unsigned long long>(st.xfers), static_cast<unsigned long long>(st.xfers_ok),
             static_cast<unsigned long long>(st.xfers_failed), static_cast<unsigned long long>(st.timeouts),
             static_cast<unsigned long long>(st.retries), static_cast<unsigned long long>(st.rx_crc_errors),
             static_cast<unsigned long long>(st.unexpected));
  } catch (const std::exception& e) {
    std::printf("Bail out! %s\n", e.what());
    return 1;
  }
  return tap.finish();
}
