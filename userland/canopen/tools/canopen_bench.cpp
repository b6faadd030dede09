// SPDX-License-Identifier: GPL-2.0
// canopen-bench: measurements for bench/canopen.sh, against a simulated
// drive on vcan. Prints "key value" lines; no pass/fail thresholds here.
//   sdo   -n NODE -d SECONDS   expedited SDO uploads back to back: round trips/s
//   pdo   -n NODE -c COUNT     RPDO1 controlword -> TPDO1 statusword latency percentiles
//   flood -d SECONDS           receive everything (cangen runs alongside): CPU share, drops
//   engine -d SECONDS          master + simulated drive in one process on the virtual bus:
//                              what the protocol code alone allows (no sockets, no scheduler)
#include <getopt.h>
#include <sys/resource.h>

#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <string>
#include <vector>

#include "advee/canopen/cia402.hpp"
#include "advee/canopen/runtime.hpp"
#include "advee/canopen/sim/drive_sim.hpp"
#include "advee/canopen/virtual_bus.hpp"

using namespace advee::canopen;
using namespace std::chrono_literals;

namespace {

double cpu_seconds() {
  rusage ru{};
  ::getrusage(RUSAGE_SELF, &ru);
  return ru.ru_utime.tv_sec + ru.ru_stime.tv_sec + (ru.ru_utime.tv_usec + ru.ru_stime.tv_usec) / 1e6;
}

// Fires `fn` once at a time point on the master's clock.
class OneShot final : public TimedService {
 public:
  explicit OneShot(Master& m) : m_(m) { reg_ = m_.attach(*this); }
  Registration reg_;
  void at(TimePoint t, std::function<void()> fn) {
    when_ = t;
    fn_ = std::move(fn);
  }
  void poll() override {
    if (fn_ && m_.now() >= when_) {
      auto f = std::move(fn_);
      fn_ = nullptr;
      f();
    }
  }
  std::optional<TimePoint> deadline() const override {
    if (!fn_) return std::nullopt;
    return when_;
  }

 private:
  Master& m_;
  TimePoint when_{};
  std::function<void()> fn_;
};

}  // namespace

int main(int argc, char** argv) {
  std::string ifname = "vcan0";
  int node = 1, seconds = 3, count = 1000;
  static const option opts[] = {{"interface", required_argument, nullptr, 'i'},
                                {"node", required_argument, nullptr, 'n'},
                                {"duration", required_argument, nullptr, 'd'},
                                {"count", required_argument, nullptr, 'c'},
                                {nullptr, 0, nullptr, 0}};
  for (int c; (c = getopt_long(argc, argv, "i:n:d:c:", opts, nullptr)) != -1;) {
    switch (c) {
      case 'i': ifname = optarg; break;
      case 'n': node = std::atoi(optarg); break;
      case 'd': seconds = std::atoi(optarg); break;
      case 'c': count = std::atoi(optarg); break;
      default: return 2;
    }
  }
  if (optind != argc - 1) {
    std::fprintf(stderr, "usage: canopen-bench [-i IF] [-n NODE] [-d S] [-c N] sdo|pdo|flood\n");
    return 2;
  }
  const std::string what = argv[optind];
  const auto n = static_cast<std::uint8_t>(node);

  if (what == "engine") {
    VirtualBus bus;
    std::unique_ptr<Master> master;
    std::unique_ptr<sim::SimulatedDrive> drive;
    const auto mp = bus.attach([&](const CanFrame& f) { master->handle(f); });
    const auto dp = bus.attach([&](const CanFrame& f) { drive->handle(f); });
    master = std::make_unique<Master>(MasterConfig{}, bus.sender(mp), system_monotonic_clock());
    drive = std::make_unique<sim::SimulatedDrive>(sim::DriveSimConfig{n, sim::DriveProfile::kEpos}, bus.sender(dp),
                                                  system_monotonic_clock());
    drive->power_on();
    bus.deliver();
    std::uint64_t done = 0;
    const TimePoint start = SteadyClock::now(), end = start + std::chrono::seconds(seconds);
    const double cpu0 = cpu_seconds();
    while (SteadyClock::now() < end) {
      for (int i = 0; i < 1000; ++i) {
        master->sdo(n).upload(0x6041, 0, [&](const SdoResult& r) { done += r.ok(); });
        bus.deliver();
      }
    }
    const double s = std::chrono::duration<double>(SteadyClock::now() - start).count();
    std::printf("engine_sdo_round_trips_per_s %.0f\nengine_cpu_us_per_round_trip %.2f\n", done / s,
                (cpu_seconds() - cpu0) * 1e6 / std::max<double>(static_cast<double>(done), 1));
    return 0;
  }

  try {
    EventLoop loop;
    MasterRuntime rt(loop, ifname, MasterConfig{});
    Master& master = rt.master();
    OneShot timer(master);
    int rc = 0;

    if (what == "sdo") {
      std::uint64_t done = 0, errors = 0;
      const TimePoint start = master.now(), end = start + std::chrono::seconds(seconds);
      std::function<void()> next = [&] {
        master.sdo(n).upload(0x6041, 0, [&](const SdoResult& r) {
          r.ok() ? ++done : ++errors;
          if (master.now() < end)
            next();
          else
            loop.stop();
        });
      };
      next();
      loop.run();
      const double s = std::chrono::duration<double>(master.now() - start).count();
      std::printf("sdo_round_trips %llu\nsdo_errors %llu\nsdo_round_trips_per_s %.0f\n",
                  static_cast<unsigned long long>(done), static_cast<unsigned long long>(errors), done / s);
      rc = errors ? 1 : 0;
    } else if (what == "pdo") {
      std::vector<double> us;
      master.nmt(NmtCommand::kStart, n);
      std::uint16_t word = 0x0006;
      TimePoint sent{};
      bool waiting = false;
      auto send = [&] {
        word = word == 0x0006 ? 0x0000 : 0x0006;  // shutdown <-> disable voltage
        sent = master.now();
        waiting = true;
        master.send(make_frame(cob::kRpdoBase[0] + n, {static_cast<std::uint8_t>(word), 0}));
      };
      const Registration tpdo = master.subscribe(cob::kTpdoBase[0] + n, [&](const CanFrame& f) {
        if (!waiting || f.len < 2) return;
        const auto s = cia402::decode(static_cast<std::uint16_t>(f.data[0] | (f.data[1] << 8)));
        const auto want = word == 0x0006 ? cia402::State::kReadyToSwitchOn : cia402::State::kSwitchOnDisabled;
        if (s != want) return;
        waiting = false;
        us.push_back(std::chrono::duration<double, std::micro>(master.now() - sent).count());
        if (static_cast<int>(us.size()) >= count) return loop.stop();
        timer.at(master.now() + 3ms, send);  // past the drive's 1 ms TPDO inhibit time
      });
      timer.at(master.now() + 100ms, [&] {
        word = 0x0000;
        send();
      });
      OneShot give_up(master);
      give_up.at(master.now() + std::chrono::seconds(seconds) + count * 50ms, [&] { loop.stop(); });
      loop.run();
      std::sort(us.begin(), us.end());
      auto pct = [&](double p) { return us.empty() ? 0.0 : us[static_cast<std::size_t>(p * (us.size() - 1))]; };
      std::printf("pdo_samples %zu\npdo_rtt_us_p50 %.0f\npdo_rtt_us_p90 %.0f\npdo_rtt_us_p99 %.0f\npdo_rtt_us_max %.0f\n",
                  us.size(), pct(0.5), pct(0.9), pct(0.99), us.empty() ? 0.0 : us.back());
      rc = static_cast<int>(us.size()) == count ? 0 : 1;
    } else if (what == "flood") {
      // A master with its usual load: heartbeat consumer for two drives,
      // heartbeat producer, every frame demultiplexed.
      std::uint64_t seen = 0;
      master.heartbeat_consumer().monitor(1, 300ms);
      master.heartbeat_consumer().monitor(2, 300ms);
      master.set_heartbeat_period(100ms);
      // Measure from the first flood frame until the bus has been quiet for
      // 500 ms (or -d seconds in all), so the CPU share is that of the flood.
      double cpu0 = 0;
      TimePoint first{}, last{};
      master.set_observer([&](const CanFrame&) {
        if (seen++ == 0) {
          first = master.now();
          cpu0 = cpu_seconds();
        }
        last = master.now();
      });
      const TimePoint give_up_at = master.now() + std::chrono::seconds(seconds);
      std::function<void()> check = [&] {
        if ((seen > 0 && master.now() - last > 500ms) || master.now() >= give_up_at) return loop.stop();
        timer.at(master.now() + 100ms, check);
      };
      timer.at(master.now() + 100ms, check);
      std::printf("ready\n");
      std::fflush(stdout);
      loop.run();
      const double cpu = seen ? cpu_seconds() - cpu0 : 0;
      const double wall = seen ? std::chrono::duration<double>(last - first).count() : 0;
      const auto& st = rt.port().stats();
      std::printf("flood_frames_received %llu\nflood_kernel_drops %u\nflood_cpu_s %.3f\nflood_wall_s %.3f\n"
                  "flood_cpu_share %.3f\nflood_cpu_us_per_frame %.2f\n",
                  static_cast<unsigned long long>(seen), st.rx_dropped, cpu, wall, cpu / std::max(wall, 1e-9),
                  seen ? cpu * 1e6 / static_cast<double>(seen) : 0.0);
    } else {
      std::fprintf(stderr, "canopen-bench: unknown measurement '%s'\n", what.c_str());
      return 2;
    }
    return rc;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "canopen-bench: %s\n", e.what());
    return 1;
  }
}
