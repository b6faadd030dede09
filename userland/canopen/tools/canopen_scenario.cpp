// SPDX-License-Identifier: GPL-2.0
// canopen-scenario: the robot's CAN motion layer (thesis 6.5) run through
// fixed scenarios against real or simulated drives, for the VM tests and the
// demo. Boots the EPOS (propulsion) and the IclA (steering), enables them,
// streams motion commands, and quick-stops the propulsion when commands stop
// for 1 s or when a drive's heartbeat is lost. Prints TAP-like progress.
#include <getopt.h>

#include <cmath>
#include <csignal>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <deque>
#include <string>

#include "advee/canopen/device_description.hpp"
#include "advee/canopen/drivers/epos.hpp"
#include "advee/canopen/drivers/icla.hpp"
#include "advee/canopen/motion_watchdog.hpp"
#include "advee/canopen/runtime.hpp"

using namespace advee::canopen;
using namespace std::chrono_literals;

namespace {

// Runs asynchronous steps one after the other on the master's clock.
class Script final : public TimedService {
 public:
  using Done = std::function<void(std::error_code)>;
  using Step = std::function<void(Done)>;

  explicit Script(Master& m) : master_(m) { reg_ = master_.attach(*this); }
  Registration reg_;

  Script& then(std::string name, Step s) {
    steps_.push_back({std::move(name), std::move(s)});
    return *this;
  }
  Script& wait(Duration d) {
    return then("", [this, d](Done done) {
      wake_at_ = master_.now() + d;
      waiting_ = std::move(done);
    });
  }
  void start(std::function<void(bool)> finished) {
    finished_ = std::move(finished);
    next();
  }
  void poll() override {
    if (waiting_ && master_.now() >= wake_at_) {
      auto d = std::move(waiting_);
      waiting_ = nullptr;
      d({});
    }
  }
  std::optional<TimePoint> deadline() const override {
    if (!waiting_) return std::nullopt;
    return wake_at_;
  }

 private:
  void next() {
    if (steps_.empty()) return finished_(true);
    auto [name, step] = std::move(steps_.front());
    steps_.pop_front();
    step([this, name](std::error_code ec) {
      if (!name.empty()) {
        ++n_;
        if (ec) {
          std::printf("not ok %d - %s: %s\n", n_, name.c_str(), ec.message().c_str());
          return finished_(false);
        }
        std::printf("ok %d - %s\n", n_, name.c_str());
      }
      next();
    });
  }

  Master& master_;
  std::deque<std::pair<std::string, Step>> steps_;
  std::function<void(bool)> finished_;
  Done waiting_;
  TimePoint wake_at_{};
  int n_ = 0;
};

// Sends the current speed every period, like the LCM motion command stream.
class CommandStream final : public TimedService {
 public:
  CommandStream(Master& m, Duration period, std::function<void()> send)
      : master_(m), period_(period), send_(std::move(send)) {
    reg_ = master_.attach(*this);
  }
  Registration reg_;
  void start() {
    running_ = true;
    next_ = master_.now();
    poll();
  }
  void stop() { running_ = false; }
  void poll() override {
    if (!running_ || master_.now() < next_) return;
    send_();
    next_ += period_;
  }
  std::optional<TimePoint> deadline() const override {
    if (!running_) return std::nullopt;
    return next_;
  }

 private:
  Master& master_;
  Duration period_;
  std::function<void()> send_;
  bool running_ = false;
  TimePoint next_{};
};

std::error_code check(bool ok) { return ok ? std::error_code{} : make_error_code(AxisError::kNotReady); }

void usage(FILE* out) {
  std::fputs(
      "usage: canopen-scenario [options] SCENARIO\n"
      "scenarios:\n"
      "  motion       boot, enable, home the steering, drive at 0.5 m/s, stop, steer to 0.3 rad\n"
      "  hb-loss      drive at 0.3 m/s until a drive's heartbeat is lost, then quick stop\n"
      "  cmd-timeout  drive at 0.3 m/s for 1 s, stop commanding: the watchdog must quick stop\n"
      "  stream       drive at 0.3 m/s until killed (the drives must stop on their own)\n"
      "  capture      propulsion only: enable, 20 speed commands, quick stop, pre-operational\n"
      "  dcf-refuse-icla  both drives boot from their descriptions (--epos-dcf, --icla-dcf): the IclA\n"
      "               must be refused as another device, the EPOS boots and drives at 0.5 m/s\n"
      "options:\n"
      "  -i, --interface IF   CAN interface (default vcan0)\n"
      "      --epos ID        EPOS node-ID (default 1)\n"
      "      --icla ID        IclA node-ID (default 2)\n"
      "      --timeout S      give up after S seconds (default 30)\n"
      "      --epos-dcf FILE  EDS/DCF of the EPOS: identity checked, configuration downloaded at boot\n"
      "      --icla-dcf FILE  EDS/DCF of the IclA, the same\n"
      "  -h, --help\n",
      out);
}

}  // namespace

int main(int argc, char** argv) {
  std::string ifname = "vcan0";
  int epos_node = 1, icla_node = 2, timeout_s = 30;
  std::string epos_dcf, icla_dcf;
  enum { kEpos = 256, kIcla, kTimeout, kEposDcf, kIclaDcf };
  static const option opts[] = {{"interface", required_argument, nullptr, 'i'},
                                {"epos", required_argument, nullptr, kEpos},
                                {"icla", required_argument, nullptr, kIcla},
                                {"timeout", required_argument, nullptr, kTimeout},
                                {"epos-dcf", required_argument, nullptr, kEposDcf},
                                {"icla-dcf", required_argument, nullptr, kIclaDcf},
                                {"help", no_argument, nullptr, 'h'},
                                {nullptr, 0, nullptr, 0}};
  for (int c; (c = getopt_long(argc, argv, "i:h", opts, nullptr)) != -1;) {
    switch (c) {
      case 'i': ifname = optarg; break;
      case kEpos: epos_node = std::atoi(optarg); break;
      case kIcla: icla_node = std::atoi(optarg); break;
      case kTimeout: timeout_s = std::atoi(optarg); break;
      case kEposDcf: epos_dcf = optarg; break;
      case kIclaDcf: icla_dcf = optarg; break;
      case 'h': usage(stdout); return 0;
      default: usage(stderr); return 2;
    }
  }
  if (optind != argc - 1) {
    usage(stderr);
    return 2;
  }
  const std::string scenario = argv[optind];
  std::setvbuf(stdout, nullptr, _IOLBF, 0);
  // The descriptions are read before any I/O: a bad file is a usage error.
  auto device = [](const std::string& path, int node, const char* name) -> std::optional<std::optional<NodeBootConfig>> {
    if (path.empty()) return std::optional<NodeBootConfig>{};
    const DescriptionResult r = load_device_description(path, static_cast<std::uint8_t>(node));
    for (const auto& e : r.errors) std::fprintf(stderr, "canopen-scenario: %s\n", e.text().c_str());
    if (!r.description) return std::nullopt;
    return std::optional<NodeBootConfig>{boot_config_from_dcf(*r.description, name)};
  };
  const auto epos_device = device(epos_dcf, epos_node, "epos");
  const auto icla_device = device(icla_dcf, icla_node, "icla");
  if (!epos_device || !icla_device) return 2;

  int exit_code = 1;
  try {
    EventLoop loop;
    MasterConfig mc;
    mc.node_id = 0x7F;
    mc.heartbeat_period = 100ms;
    MasterRuntime rt(loop, ifname, mc);
    Master& master = rt.master();

    drivers::EposConfig ec;
    ec.node = static_cast<std::uint8_t>(epos_node);
    ec.drive.device = *epos_device;
    drivers::EposDriver epos(master, ec);
    drivers::IclaConfig ic;
    ic.node = static_cast<std::uint8_t>(icla_node);
    ic.homing_speed = 4000;
    ic.drive.device = *icla_device;
    drivers::IclaDriver icla(master, ic);

    double speed = 0;
    std::function<void()> on_command;  // feeds the watchdog, set below
    CommandStream stream(master, 50ms, [&] {
      epos.set_speed(speed);
      if (on_command) on_command();
    });
    std::optional<TimePoint> watchdog_fired;
    // Taken just before each feed: the watchdog counts from its feed, which
    // comes after the PDO send, so the stream's own send time would be late
    // by a system call (2 ms on the debug kernel) and fail a correct watchdog.
    TimePoint last_command{};
    Script script(master);
    bool expect_watchdog = false;
    MotionWatchdog watchdog(master, 1s, [&] {
      watchdog_fired = master.now();
      std::printf("# motion command timeout: quick stop\n");
      epos.quick_stop([&](std::error_code e) {
        if (!expect_watchdog) return;
        const auto gap = std::chrono::duration_cast<std::chrono::milliseconds>(*watchdog_fired - last_command);
        std::printf("# quick stop %s, %lld ms after the last command\n", e ? e.message().c_str() : "done",
                    static_cast<long long>(gap.count()));
        const bool ok = !e && gap >= 1000ms && epos.drive().axis().state() == cia402::State::kQuickStopActive;
        std::printf("%s - watchdog quick stop after 1 s without commands\n", ok ? "ok" : "not ok");
        exit_code = ok ? 0 : 1;
        loop.stop();
      });
    });
    // Each motion command feeds the watchdog, whatever the scenario.
    on_command = [&] {
      last_command = master.now();
      watchdog.feed();
    };
    auto drive_at = [&](double v) {
      speed = v;
      stream.start();
    };
    // Steps: drive at 0.5 m/s, and after 1.5 s the EPOS's TxPDO4 reports it.
    auto drive_and_measure = [&] {
      script
          .then("drive at 0.5 m/s", [&](auto d) {
            drive_at(0.5);
            d({});
          })
          .wait(1500ms)
          .then("EPOS reports 0.5 m/s on TxPDO4", [&](auto d) {
            const auto v = epos.speed();
            std::printf("# measured %.4f m/s\n", v.value_or(NAN));
            d(check(v && std::fabs(*v - 0.5) < 0.005));
          });
    };
    auto events = [&](const DriveEvent& e) {
      std::printf("# event: %s\n", e.text.c_str());
      if (e.kind == DriveEventKind::kHeartbeatLost && scenario == "hb-loss") {
        stream.stop();
        const unsigned node = e.node;
        epos.quick_stop([&, node](std::error_code err) {
          const bool ok = !err && epos.drive().axis().state() == cia402::State::kQuickStopActive;
          std::printf("%s - propulsion quick stop after heartbeat loss of node %u\n", ok ? "ok" : "not ok", node);
          exit_code = ok ? 0 : 1;
          loop.stop();
        });
      }
    };
    epos.drive().on_event(events);
    icla.drive().on_event(events);

    auto with_error = [](Drive402& drive, Script::Done d) {
      return [&drive, d](std::error_code e) {
        if (e && !drive.boot_error().empty()) std::printf("# %s\n", drive.boot_error().c_str());
        d(e);
      };
    };
    auto boot_epos = [&] {
      script.then("boot EPOS (node " + std::to_string(epos_node) + ")",
                  [&](auto d) { epos.boot(with_error(epos.drive(), d)); });
    };
    auto boot_icla = [&] {
      script.then("boot IclA (node " + std::to_string(icla_node) + ")",
                  [&](auto d) { icla.boot(with_error(icla.drive(), d)); });
    };
    auto finish = [&](bool ok) {
      if (!ok || (scenario != "hb-loss" && scenario != "cmd-timeout" && scenario != "stream")) {
        exit_code = ok ? 0 : 1;
        loop.stop();
      }
    };

    if (scenario == "motion") {
      boot_epos();
      boot_icla();
      script.then("enable EPOS", [&](auto d) { epos.enable(d); })
          .then("enable IclA", [&](auto d) { icla.enable(d); })
          .then("IclA homing on the home switch", [&](auto d) { icla.home(d); })
          .then("IclA position is the home offset", [&](auto d) { d(check(icla.angle() && *icla.angle() == 0.0)); });
      drive_and_measure();
      script.then("stop", [&](auto d) {
            speed = 0;
            d({});
          })
          .wait(800ms)
          .then("EPOS at standstill", [&](auto d) { d(check(epos.speed() && *epos.speed() == 0.0)); })
          .then("steer to 0.3 rad", [&](auto d) { icla.set_angle(0.3, d); })
          .then("IclA reports 0.3 rad on TPDO2", [&](auto d) { d(check(icla.angle() && std::fabs(*icla.angle() - 0.3) < 1e-9)); })
          .then("disable EPOS", [&](auto d) {
            stream.stop();
            epos.drive().disable(d);
          })
          .then("disable IclA", [&](auto d) { icla.drive().disable(d); });
    } else if (scenario == "hb-loss" || scenario == "stream") {
      boot_epos();
      boot_icla();
      script.then("enable EPOS", [&](auto d) { epos.enable(d); })
          .then("enable IclA", [&](auto d) { icla.enable(d); })
          .then("streaming 0.3 m/s", [&](auto d) {
            drive_at(0.3);
            d({});
          });
    } else if (scenario == "cmd-timeout") {
      expect_watchdog = true;
      boot_epos();
      script.then("enable EPOS", [&](auto d) { epos.enable(d); })
          .then("streaming 0.3 m/s", [&](auto d) {
            drive_at(0.3);
            d({});
          })
          .wait(1s)
          .then("commands stopped", [&](auto d) {
            stream.stop();
            d({});
          });
    } else if (scenario == "capture") {
      boot_epos();
      script.then("enable EPOS", [&](auto d) { epos.enable(d); });
      for (int i = 1; i <= 20; ++i)
        script.then("", [&, i](auto d) {
          epos.set_speed(0.01 * i);
          watchdog.feed();
          d({});
        }).wait(20ms);
      script.then("quick stop", [&](auto d) { epos.quick_stop(d); })
          .then("pre-operational", [&](auto d) {
            master.nmt(NmtCommand::kEnterPreOperational, static_cast<std::uint8_t>(epos_node));
            d({});
          })
          .wait(50ms);
    } else if (scenario == "dcf-refuse-icla") {
      script.then("IclA (node " + std::to_string(icla_node) + ") refused as another device", [&](auto d) {
        icla.boot([&, d](std::error_code e) {
          std::printf("# %s\n", icla.drive().boot_error().c_str());
          d(check(e == make_error_code(BootError::kWrongDevice)));
        });
      });
      boot_epos();
      script.then("enable EPOS", [&](auto d) { epos.enable(d); });
      drive_and_measure();
      script.then("disable EPOS", [&](auto d) {
        stream.stop();
        epos.drive().disable(d);
      });
    } else {
      std::fprintf(stderr, "canopen-scenario: unknown scenario '%s'\n", scenario.c_str());
      return 2;
    }

    SignalHandler signals(loop, {SIGINT, SIGTERM}, [&](int) { loop.stop(); });
    struct GiveUp final : TimedService {
      Master& m;
      TimePoint at;
      EventLoop& loop;
      GiveUp(Master& mm, TimePoint t, EventLoop& l) : m(mm), at(t), loop(l) { reg_ = m.attach(*this); }
      Registration reg_;
      void poll() override {
        if (m.now() >= at) {
          std::printf("not ok - scenario timed out\n");
          loop.stop();
        }
      }
      std::optional<TimePoint> deadline() const override {
        if (at == TimePoint::max()) return std::nullopt;
        return at;
      }
    } give_up(master, master.now() + std::chrono::seconds(timeout_s), loop);
    if (scenario == "stream") give_up.at = TimePoint::max();

    script.start(finish);
    loop.run();
    const auto& s = rt.port().stats();
    std::printf("# bus: %llu frames in, %llu out, %llu ENOBUFS retries, %u dropped by the kernel\n",
                static_cast<unsigned long long>(s.rx_frames), static_cast<unsigned long long>(s.tx_frames),
                static_cast<unsigned long long>(s.tx_retries), s.rx_dropped);
  } catch (const std::exception& e) {
    std::fprintf(stderr, "canopen-scenario: %s\n", e.what());
    return 1;
  }
  return exit_code;
}
