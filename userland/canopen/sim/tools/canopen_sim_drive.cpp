// SPDX-License-Identifier: GPL-2.0
// canopen-sim-drive: one simulated CiA 402 drive on a SocketCAN interface
// (vcan in the tests), as its own process. Fault injection at start-up by
// option, at run time by signal: SIGUSR1 = EMCY 0x4210 + fault, SIGUSR2 =
// heartbeat silence on/off. Prints one line per state change on stdout.
#include <getopt.h>

#include <csignal>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <map>
#include <string>

#include "advee/canopen/can_port.hpp"
#include "advee/canopen/event_loop.hpp"
#include "advee/canopen/runtime.hpp"
#include "advee/canopen/sim/drive_sim.hpp"

using namespace advee::canopen;

namespace {

void usage(FILE* out) {
  std::fputs(
      "usage: canopen-sim-drive [options]\n"
      "  -i, --interface IF          CAN interface (default vcan0)\n"
      "  -n, --node ID               node-ID 1..127 (default 1)\n"
      "  -p, --profile epos|icla     object dictionary and PDO defaults (default epos)\n"
      "      --home-switch POS       position of the home switch (default -3000)\n"
      "      --step-ms MS            dynamics step (default 1)\n"
      "      --sdo-delay-ms MS       answer SDO requests this late\n"
      "      --refuse-transition-16  quick stop active stays on enable operation\n"
      "      --refuse-mode-while-halt  0x6061 ignores 0x6060 while halt is set\n"
      "      --no-home-switch        homing ends in a homing error\n"
      "      --sdo-abort IDX:SUB=CODE  answer SDO access to the object with this abort code (hex)\n"
      "  -h, --help\n"
      "signals: SIGUSR1 inject EMCY 0x4210 + fault, SIGUSR2 toggle heartbeat silence\n",
      out);
}

}  // namespace

int main(int argc, char** argv) {
  std::string ifname = "vcan0";
  sim::DriveSimConfig cfg;
  sim::DriveFaults faults;
  int sdo_delay_ms = 0;
  std::map<std::pair<std::uint16_t, std::uint8_t>, SdoAbort> aborts;
  enum { kHome = 256, kStep, kDelay, kT16, kHalt, kNoSwitch, kAbort };
  static const option opts[] = {{"interface", required_argument, nullptr, 'i'},
                                {"node", required_argument, nullptr, 'n'},
                                {"profile", required_argument, nullptr, 'p'},
                                {"home-switch", required_argument, nullptr, kHome},
                                {"step-ms", required_argument, nullptr, kStep},
                                {"sdo-delay-ms", required_argument, nullptr, kDelay},
                                {"refuse-transition-16", no_argument, nullptr, kT16},
                                {"refuse-mode-while-halt", no_argument, nullptr, kHalt},
                                {"no-home-switch", no_argument, nullptr, kNoSwitch},
                                {"sdo-abort", required_argument, nullptr, kAbort},
                                {"help", no_argument, nullptr, 'h'},
                                {nullptr, 0, nullptr, 0}};
  for (int c; (c = getopt_long(argc, argv, "i:n:p:h", opts, nullptr)) != -1;) {
    switch (c) {
      case 'i': ifname = optarg; break;
      case 'n': {
        const int n = std::atoi(optarg);
        if (!is_valid_node_id(static_cast<unsigned>(n))) {
          std::fprintf(stderr, "canopen-sim-drive: node-ID must be 1..127\n");
          return 2;
        }
        cfg.node = static_cast<std::uint8_t>(n);
        break;
      }
      case 'p':
        if (!std::strcmp(optarg, "epos")) {
          cfg.profile = sim::DriveProfile::kEpos;
        } else if (!std::strcmp(optarg, "icla")) {
          cfg.profile = sim::DriveProfile::kIcla;
          cfg.position_per_velocity = 1.0;
        } else {
          std::fprintf(stderr, "canopen-sim-drive: unknown profile '%s'\n", optarg);
          return 2;
        }
        break;
      case kHome: cfg.home_switch_position = std::atof(optarg); break;
      case kStep: cfg.step = std::chrono::milliseconds(std::max(1, std::atoi(optarg))); break;
      case kDelay: sdo_delay_ms = std::atoi(optarg); break;
      case kT16: faults.refuse_transition_16 = true; break;
      case kHalt: faults.refuse_mode_change_while_halt = true; break;
      case kNoSwitch: faults.homing_switch_missing = true; break;
      case kAbort: {
        unsigned idx, sub, code;
        if (std::sscanf(optarg, "%x:%x=%x", &idx, &sub, &code) != 3 || idx > 0xFFFF || sub > 0xFF) {
          std::fprintf(stderr, "canopen-sim-drive: --sdo-abort wants INDEX:SUB=CODE in hex\n");
          return 2;
        }
        aborts[{static_cast<std::uint16_t>(idx), static_cast<std::uint8_t>(sub)}] = static_cast<SdoAbort>(code);
        break;
      }
      case 'h': usage(stdout); return 0;
      default: usage(stderr); return 2;
    }
  }
  std::setvbuf(stdout, nullptr, _IOLBF, 0);

  try {
    EventLoop loop;
    std::unique_ptr<sim::SimulatedDrive> drive;
    CanPort port(loop, CanSocket::open(ifname), [&drive](const CanFrame& f) { drive->handle(f); });
    drive = std::make_unique<sim::SimulatedDrive>(cfg, port.sender(), system_monotonic_clock());
    drive->faults() = faults;
    drive->sdo().faults().response_delay = std::chrono::milliseconds(sdo_delay_ms);
    drive->sdo().faults().abort_on = aborts;

    auto state = drive->state();
    auto nmt = drive->nmt_state();
    auto report = [&] {
      if (drive->nmt_state() != nmt) {
        nmt = drive->nmt_state();
        std::printf("node %u nmt %s\n", cfg.node, std::string(to_string(nmt)).c_str());
      }
      if (drive->state() != state) {
        state = drive->state();
        std::printf("node %u state %s\n", cfg.node, std::string(cia402::to_string(state)).c_str());
      }
    };
    loop.add_timer_source([&] { return drive->deadline(); },
                          [&] {
                            drive->poll();
                            report();
                          });
    SignalHandler signals(loop, {SIGINT, SIGTERM, SIGUSR1, SIGUSR2}, [&](int sig) {
      if (sig == SIGUSR1) {
        std::printf("node %u inject EMCY 0x4210\n", cfg.node);
        drive->inject_fault(0x4210);
      } else if (sig == SIGUSR2) {
        drive->faults().heartbeat_silent = !drive->faults().heartbeat_silent;
        std::printf("node %u heartbeat %s\n", cfg.node, drive->faults().heartbeat_silent ? "silent" : "on");
      } else {
        loop.stop();
      }
    });
    drive->power_on();
    std::printf("node %u ready on %s (%s)\n", cfg.node, ifname.c_str(),
                cfg.profile == sim::DriveProfile::kEpos ? "epos" : "icla");
    loop.run();
    std::printf("node %u exit: %llu RPDOs in, %llu TPDOs out, %llu SDO requests\n", cfg.node,
                static_cast<unsigned long long>(drive->rpdos_received()),
                static_cast<unsigned long long>(drive->tpdos_sent()),
                static_cast<unsigned long long>(drive->sdo().requests()));
  } catch (const std::exception& e) {
    std::fprintf(stderr, "canopen-sim-drive: %s\n", e.what());
    return 1;
  }
  return 0;
}
