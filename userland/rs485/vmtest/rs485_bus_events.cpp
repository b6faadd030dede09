// SPDX-License-Identifier: GPL-2.0
// rs485-bus-events: VM check of Bus's event thread over the real stack
// (simulated FPGA -> ts-uart -> n_rs485 -> Bus) with advee-rs485-sim serving a
// PSC1 on a full-duplex bus. TAP 13 on stdout; exit 1 if a check failed.
//
//   rs485-bus-events RS485_SIM CONTROL_SOCKET [TTY [PSC1_ADDR]]
//
// Checks what a user of the library would notice: PSC1 PAUSE/POWER callbacks
// while another thread polls the same node, on_closed (and no hang) when
// another process detaches the discipline or the tty hangs up, transactions
// failing with a system error afterwards, destruction with a running thread.
#include <fcntl.h>
#include <sys/ioctl.h>
#include <unistd.h>

#include <atomic>
#include <chrono>
#include <cstdarg>
#include <cstdio>
#include <cstdlib>
#include <memory>
#include <string>
#include <thread>

#include "advee/rs485/bus.hpp"
#include "advee/rs485/devices/psc1.hpp"

using namespace advee::rs485;
using namespace std::chrono_literals;

namespace {

int tests = 0, failures = 0;

void check(bool ok, const char* fmt, ...) {
  va_list ap;
  va_start(ap, fmt);
  std::printf("%s %d - ", ok ? "ok" : "not ok", ++tests);
  std::vprintf(fmt, ap);
  std::printf("\n");
  std::fflush(stdout);
  va_end(ap);
  if (!ok) ++failures;
}

template <typename Pred>
bool wait_until(Pred p, std::chrono::milliseconds limit) {
  const auto end = std::chrono::steady_clock::now() + limit;
  while (!p()) {
    if (std::chrono::steady_clock::now() > end) return false;
    std::this_thread::sleep_for(20ms);
  }
  return true;
}

constexpr int kEvents = 20;

// Destroys the bus and tells whether that took less than a second (the event
// thread must stop without waiting for anything on the line).
bool destroyed_promptly(std::unique_ptr<Bus>& bus) {
  const auto t0 = std::chrono::steady_clock::now();
  bus.reset();
  return std::chrono::steady_clock::now() - t0 < 1s;
}

}  // namespace

int main(int argc, char** argv) {
  if (argc < 3) {
    std::fprintf(stderr, "usage: rs485-bus-events RS485_SIM CONTROL_SOCKET [TTY [PSC1_ADDR]]\n");
    return 2;
  }
  const std::string sim = argv[1], sock = argv[2];
  const std::string tty = argc > 3 ? argv[3] : "/dev/ttyTSU2";
  const auto addr = static_cast<std::uint8_t>(argc > 4 ? std::strtoul(argv[4], nullptr, 0) : 0x01);
  char psc_name[16];
  std::snprintf(psc_name, sizeof(psc_name), "psc1@0x%02x", addr);
  auto sim_cmd = [&](const std::string& cmd) {
    return std::system((sim + " --control " + sock + " --send '" + cmd + "' >/dev/null").c_str()) == 0;
  };
  std::printf("TAP version 13\n1..10\n");
  try {
    {
      BusOptions o;
      o.config = BusConfig{115200, 100ms, 2, 2};  // TCG latencies
      auto owner = std::make_unique<Bus>(tty, o);
      Bus& bus = *owner;
      Psc1 psc(bus, addr);
      std::atomic<int> pauses{0}, powers{0};
      std::atomic<bool> closed{false};
      std::error_code why;
      auto s1 = psc.on_pause([&](const PauseEvent& e) {
        if (e.engaged && e.sources == 3) ++pauses;
      });
      auto s2 = psc.on_power([&](const PowerEvent&) { ++powers; });
      auto s3 = bus.subscribe([](const Frame&) {}, [&](std::error_code ec) {
        why = ec;
        closed = true;
      });
      std::atomic<bool> stop{false};
      std::atomic<int> polls_ok{0}, polls_failed{0};
      std::thread poller([&] {
        while (!stop) psc.currents() ? ++polls_ok : ++polls_failed;
      });
      bool sent = true;
      for (int i = 0; i < kEvents; ++i)
        sent = sim_cmd("event " + std::string(psc_name) + " pause 1 3") &&
               sim_cmd("event " + std::string(psc_name) + " power") && sent;
      wait_until([&] { return pauses == kEvents && powers == kEvents; }, 5s);
      stop = true;
      poller.join();
      check(sent && pauses == kEvents, "%d PAUSE events reach on_pause while another thread polls the node (%d)",
            kEvents, pauses.load());
      check(powers == kEvents, "%d POWER events reach on_power (%d)", kEvents, powers.load());
      check(polls_ok > 0 && polls_failed == 0, "GET_CURRENTS during the events: %d OK, %d failed", polls_ok.load(),
            polls_failed.load());
      // Another process detaches the discipline (sets N_TTY).
      const int fd = ::open(tty.c_str(), O_RDWR | O_NOCTTY | O_NONBLOCK);
      int n_tty = 0;
      const bool detached = fd >= 0 && ::ioctl(fd, TIOCSETD, &n_tty) == 0;
      wait_until([&] { return closed.load(); }, 5s);
      check(detached && closed && why == std::errc::not_connected, "on_closed(ENOTCONN) after a detach: %s",
            why.message().c_str());
      const auto r = bus.transact({addr, standard_instr::kGetFirmwareVersion});
      check(r.error == std::errc::not_connected, "transact after the detach: ENOTCONN (%s)", r.error.message().c_str());
      if (fd >= 0) ::close(fd);
      s1.reset();
      s2.reset();
      s3.reset();
      check(destroyed_promptly(owner), "Bus destroyed at once after the detach");
    }
    {
      auto owner = std::make_unique<Bus>(tty);  // attaches again
      std::atomic<int> n{0};
      auto s = owner->subscribe([&](const Frame&) { ++n; });
      sim_cmd("event " + std::string(psc_name) + " power");
      wait_until([&] { return n > 0; }, 5s);
      check(n == 1, "a re-attached bus gets the next event (%d)", n.load());
      check(destroyed_promptly(owner), "Bus destroyed at once with its event thread waiting");
      s.reset();  // after the Bus: harmless
    }
    {
      Bus bus(tty);
      std::atomic<bool> closed{false};
      std::error_code why;
      auto s = bus.subscribe([](const Frame&) {}, [&](std::error_code ec) {
        why = ec;
        closed = true;
      });
      const int fd = ::open(tty.c_str(), O_RDWR | O_NOCTTY | O_NONBLOCK);
      const bool hung = fd >= 0 && ::ioctl(fd, TIOCVHANGUP) == 0;
      wait_until([&] { return closed.load(); }, 5s);
      check(hung && closed && why == std::errc::io_error, "on_closed(EIO) after a hangup: %s", why.message().c_str());
      const auto r = bus.transact({addr, standard_instr::kGetFirmwareVersion});
      check(r.error && !is_protocol_outcome(r.error), "transact after the hangup: a system error (%s)",
            r.error.message().c_str());
      if (fd >= 0) ::close(fd);
    }
  } catch (const std::exception& e) {
    std::printf("Bail out! %s\n", e.what());
    return 1;
  }
  return failures ? 1 : 0;
}
