// SPDX-License-Identifier: GPL-2.0
// advee-rs485-sim: the robot's RS-485 boards (BR-SD1, BR-SO1, BR-SBS1, BR-PSC1) as
// behavioural models on the simulated FPGA's wires, several buses in one
// process, configured by a YAML file and steered through a control socket.
#include <fcntl.h>
#include <poll.h>
#include <signal.h>
#include <sys/socket.h>
#include <sys/un.h>
#include <unistd.h>

#include <CLI/CLI.hpp>
#include <cerrno>
#include <cstdio>
#include <cstring>
#include <ctime>
#include <string>
#include <vector>

#include "advee/cli.hpp"
#include "advee/rs485sim/config.hpp"
#include "advee/rs485sim/control.hpp"
#include "advee/rs485sim/control_client.hpp"
#include "advee/signal_fd.hpp"
#include "advee/unique_fd.hpp"

using namespace advee::rs485sim;
using advee::UniqueFd;

namespace {

constexpr const char* kDescription =
    "advee-rs485-sim - simulated RS-485 boards of the Advee robot\n"
    "\n"
    "Answers the robot's 9-bit multidrop protocol (shared/specs/rs485-protocol.md) as\n"
    "the boards BR-SD1 (8 ultrasonic + 2 infrared distances, PAUSE sources), BR-SO1\n"
    "(two wheel encoders, counters of 1/2/4 bytes that wrap), BR-SBS1 (beacon\n"
    "bearings) and BR-PSC1 (8 power channels, currents, PAUSE/POWER events) would,\n"
    "on the wires of the simulated TS-7800 FPGA (/dev/ts7800-sim/uartN is the far\n"
    "end of /dev/ttyTSUn; modprobe ts_uart ts7800_sim first). One process serves\n"
    "every bus of the configuration file.\n";

constexpr const char* kFooter =
    "CONFIGURATION (YAML, see docs/rs485-sim.md):\n"
    "  control: /run/rs485-sim.sock   # control socket (optional)\n"
    "  seed: 1                        # random seed of response times and faults\n"
    "  buses:\n"
    "    - name: a\n"
    "      wire: /dev/ts7800-sim/uart0\n"
    "      duplex: half               # half (default) or full (events allowed)\n"
    "      devices:\n"
    "        - {type: sd1, address: 0x10, srf_m: [1.0, 2.5, null], ir_m: [0.2, 0.1]}\n"
    "        - {type: so1, address: 0x20, rate: [100, 100], faults: {bad_crc: 0.01}}\n"
    "  Per device: type, address, firmware [MAJ, MIN], response_us N or [MIN, MAX],\n"
    "  faults {no_answer, bad_crc, unkinstr, slow: PROBABILITY|once|once:N; slow_ms},\n"
    "  sd1: srf_m, ir_m, pause_sources; so1: ticks, rate; sbs1: ids, beacons\n"
    "  [{id, bearing_deg, quality}]; psc1: status, currents_a, pause_period_ms,\n"
    "  power_period_ms.\n"
    "\n"
    "CONTROL COMMANDS (one per datagram on the control socket, or --send):\n"
    "  set sd1@0x10 srf 3 1.25        # metres; 'none' = no echo\n"
    "  set so1@0x20 ticks 100 -5      event psc1@0x01 pause 1 0x01\n"
    "  fault sd1@0x10 bad-crc once    stats sd1@0x10\n"
    "  'help' lists them all; the reply starts with 'ok' or 'error:'.\n"
    "\n"
    "SIGNALS: SIGTERM, SIGINT: stop, print each device's counters on stderr, exit 0.\n"
    "\n"
    "EXIT STATUS: 0 stopped by a signal or command answered 'ok'; 1 bad configuration file,\n"
    "error at run time or command answered 'error:'; 2 bad command line.\n"
    "\n"
    "EXAMPLES:\n"
    "  advee-rs485-sim -c robot.yaml -v\n"
    "  advee-rs485-sim --control /run/rs485-sim.sock --send 'set sd1@0x10 srf all 0.8'\n";

std::string timestamp() {
  timespec ts{};
  clock_gettime(CLOCK_MONOTONIC, &ts);
  char buf[32];
  std::snprintf(buf, sizeof(buf), "%ld.%06ld", static_cast<long>(ts.tv_sec), ts.tv_nsec / 1000);
  return buf;
}

sockaddr_un unix_address(const std::string& path) {
  sockaddr_un a{};
  a.sun_family = AF_UNIX;
  if (path.size() >= sizeof(a.sun_path)) throw std::runtime_error("socket path too long: " + path);
  std::memcpy(a.sun_path, path.c_str(), path.size() + 1);
  return a;
}

// Client mode: one command, the reply on stdout.
int send_command(const std::string& path, const std::string& cmd) {
  try {
    const std::string reply = control_request(path, cmd);
    std::printf("%s\n", reply.c_str());
    return reply.rfind("ok", 0) == 0 ? 0 : 1;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "advee-rs485-sim: %s\n", e.what());
    return 1;
  }
}

bool write_words(int fd, const std::vector<std::uint16_t>& w) {
  std::size_t done = 0;
  const std::size_t bytes = w.size() * sizeof(std::uint16_t);
  const auto* p = reinterpret_cast<const char*>(w.data());
  while (done < bytes) {
    const ssize_t r = write(fd, p + done, bytes - done);
    if (r >= 0) {
      done += static_cast<std::size_t>(r);
    } else if (errno == EAGAIN) {
      // The UART's receive queue is full (line off or slow): wait for room.
      pollfd pf{fd, POLLOUT, 0};
      if (poll(&pf, 1, 1000) == 0) return false;
    } else if (errno != EINTR) {
      return false;
    }
  }
  return true;
}

struct Wire {
  BusSim* bus;
  std::string path;
  UniqueFd fd;
};

int run(SimConfig& cfg, bool verbose) {
  std::vector<Wire> wires;
  std::vector<BusSim*> buses;
  for (auto& b : cfg.buses) {
    UniqueFd fd(open(b.wire.c_str(), O_RDWR | O_NONBLOCK | O_CLOEXEC));
    if (!fd) {
      std::fprintf(stderr, "advee-rs485-sim: bus %s: %s: %s%s\n", b.bus->name().c_str(), b.wire.c_str(),
                   std::strerror(errno), errno == ENOENT ? " (modprobe ts_uart ts7800_sim?)" : "");
      return 1;
    }
    wires.push_back({b.bus.get(), b.wire, std::move(fd)});
    buses.push_back(b.bus.get());
  }
  Control control(buses);
  control.set_logging(verbose);
  for (auto* b : buses)
    b->set_logger([&control](const std::string& line) {
      if (control.logging()) std::fprintf(stderr, "%s %s\n", timestamp().c_str(), line.c_str());
    });

  UniqueFd ctl;
  if (!cfg.control.empty()) {
    ctl.reset(socket(AF_UNIX, SOCK_DGRAM | SOCK_CLOEXEC | SOCK_NONBLOCK, 0));
    const auto a = unix_address(cfg.control);
    unlink(cfg.control.c_str());  // a stale socket of an earlier run
    if (!ctl || bind(ctl.get(), reinterpret_cast<const sockaddr*>(&a), sizeof(a))) {
      std::fprintf(stderr, "advee-rs485-sim: control socket %s: %s\n", cfg.control.c_str(), std::strerror(errno));
      return 1;
    }
  }

  std::optional<advee::SignalFd> sfd;
  try {
    sfd.emplace(std::initializer_list<int>{SIGTERM, SIGINT});
  } catch (const std::system_error& e) {
    std::fprintf(stderr, "advee-rs485-sim: %s\n", e.what());
    return 1;
  }

  std::string ready = "advee-rs485-sim: ready:";
  for (const auto& w : wires) {
    ready += " bus " + w.bus->name() + " on " + w.path + " (";
    for (const auto& d : w.bus->devices()) ready += (d == w.bus->devices().front() ? "" : " ") + d->name();
    ready += ")";
  }
  if (!cfg.control.empty()) ready += "; control " + cfg.control;
  std::printf("%s\n", ready.c_str());
  std::fflush(stdout);

  std::vector<pollfd> pfds;
  for (const auto& w : wires) pfds.push_back({w.fd.get(), POLLIN, 0});
  pfds.push_back({sfd->fd(), POLLIN, 0});
  if (ctl) pfds.push_back({ctl.get(), POLLIN, 0});
  const std::size_t sig_i = wires.size(), ctl_i = wires.size() + 1;

  int rc = 0;
  for (bool stop = false; !stop;) {
    auto now = Clock::now();
    std::optional<Clock::time_point> deadline;
    for (auto& w : wires) {
      w.bus->poll(now);
      for (const auto& tx : w.bus->take_due(now))
        if (!write_words(w.fd.get(), tx.words))
          std::fprintf(stderr, "advee-rs485-sim: bus %s: writing %s: %s\n", w.bus->name().c_str(), w.path.c_str(),
                       errno ? std::strerror(errno) : "no room for 1 s");
      if (auto d = w.bus->next_deadline(); d && (!deadline || *d < *deadline)) deadline = d;
    }
    timespec ts{}, *tsp = nullptr;
    if (deadline) {
      const auto ns = std::max<long long>(0, std::chrono::duration_cast<std::chrono::nanoseconds>(*deadline - now).count());
      ts.tv_sec = static_cast<time_t>(ns / 1000000000);
      ts.tv_nsec = static_cast<long>(ns % 1000000000);
      tsp = &ts;
    }
    if (ppoll(pfds.data(), pfds.size(), tsp, nullptr) < 0) {
      if (errno == EINTR) continue;
      std::perror("advee-rs485-sim: ppoll");
      rc = 1;
      break;
    }
    for (std::size_t i = 0; i < wires.size(); ++i) {
      if (pfds[i].revents & (POLLERR | POLLHUP | POLLNVAL)) {
        std::fprintf(stderr, "advee-rs485-sim: bus %s: %s went away\n", wires[i].bus->name().c_str(), wires[i].path.c_str());
        rc = 1;
        stop = true;
      }
      if (!(pfds[i].revents & POLLIN)) continue;
      std::uint16_t buf[4096];
      const ssize_t n = read(wires[i].fd.get(), buf, sizeof(buf));
      if (n > 0)
        wires[i].bus->feed(std::span<const std::uint16_t>(buf, static_cast<std::size_t>(n) / 2), Clock::now());
    }
    if (ctl && (pfds[ctl_i].revents & POLLIN)) {
      char buf[1024];
      sockaddr_un from{};
      socklen_t fromlen = sizeof(from);
      const ssize_t n = recvfrom(ctl.get(), buf, sizeof(buf), 0, reinterpret_cast<sockaddr*>(&from), &fromlen);
      if (n >= 0) {
        std::string cmd(buf, static_cast<std::size_t>(n));
        while (!cmd.empty() && (cmd.back() == '\n' || cmd.back() == '\r')) cmd.pop_back();
        const std::string reply = control.execute(cmd, Clock::now());
        if (control.logging()) std::fprintf(stderr, "%s control: %s -> %s\n", timestamp().c_str(), cmd.c_str(),
                                            reply.substr(0, reply.find('\n')).c_str());
        if (fromlen > sizeof(sa_family_t))
          sendto(ctl.get(), reply.data(), reply.size(), MSG_DONTWAIT, reinterpret_cast<sockaddr*>(&from), fromlen);
      }
    }
    if (pfds[sig_i].revents & POLLIN) {
      if (const auto si = sfd->read())
        std::fprintf(stderr, "advee-rs485-sim: %s, stopping\n", strsignal(static_cast<int>(si->ssi_signo)));
      stop = true;
    }
  }

  for (const auto& w : wires) {
    const auto& r = w.bus->receiver_stats();
    std::fprintf(stderr, "advee-rs485-sim: bus %s: frames=%llu crc_errors=%llu truncated=%llu noise=%llu\n",
                 w.bus->name().c_str(), static_cast<unsigned long long>(r.frames),
                 static_cast<unsigned long long>(r.crc_errors), static_cast<unsigned long long>(r.truncated),
                 static_cast<unsigned long long>(r.noise));
    for (const auto& d : w.bus->devices())
      std::fprintf(stderr, "advee-rs485-sim: %s:%s %s\n", w.bus->name().c_str(), d->name().c_str(),
                   control.execute("stats " + w.bus->name() + ":" + d->name(), Clock::now()).substr(3).c_str());
  }
  if (!cfg.control.empty()) unlink(cfg.control.c_str());
  return rc;
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app(kDescription, "advee-rs485-sim");
  app.footer(kFooter);
  std::string config, control, send;
  bool verbose = false, check = false;
  std::uint32_t seed = 0;
  app.add_option("-c,--config", config, "YAML configuration file (buses, devices, faults)")->type_name("FILE");
  app.add_option("--control", control, "control socket path (overrides the file's 'control')")->type_name("PATH");
  app.add_option("--seed", seed, "random seed (overrides the file's 'seed'); same seed, same faults")->type_name("N");
  app.add_flag("-v,--verbose", verbose, "log every frame and control command on stderr ('log on|off' toggles)");
  app.add_flag("--check", check, "load the configuration, report errors, exit");
  app.add_option("--send", send, "client mode: send one control command to --control and print the reply")
      ->type_name("COMMAND");
  ADVEE_CLI_PARSE(app, argc, argv);

  if (!send.empty()) {
    if (control.empty()) return advee::cli::usage_error(app, "--send needs --control PATH");
    return send_command(control, send);
  }
  if (config.empty()) return advee::cli::usage_error(app, "--config FILE is required");
  try {
    SimConfig cfg = load_config_file(config, app.count("--seed") ? std::optional(seed) : std::nullopt);
    if (!control.empty()) cfg.control = control;
    if (check) {
      std::printf("%s: ok (%zu buses)\n", config.c_str(), cfg.buses.size());
      return 0;
    }
    return run(cfg, verbose);
  } catch (const std::exception& e) {  // ConfigError too: the file is read at run time
    std::fprintf(stderr, "advee-rs485-sim: %s\n", e.what());
    return 1;
  }
}
