// SPDX-License-Identifier: GPL-2.0
// advee-canopen-sim-drive: one simulated CiA 402 drive on a SocketCAN interface
// (vcan in the tests), as its own process. Fault injection at start-up by
// option, at run time by signal: SIGUSR1 = EMCY 0x4210 + fault, SIGUSR2 =
// heartbeat silence on/off. Prints one line per state change on stdout.
// An LSS slave (CiA 305) sits in front of the drive: with --unconfigured it
// has no node-ID and answers LSS only until a master gives it one.
#include <CLI/CLI.hpp>
#include <csignal>
#include <cstdio>
#include <map>
#include <string>

#include "advee/canopen/can_port.hpp"
#include "advee/canopen/device_description.hpp"
#include "advee/canopen/event_loop.hpp"
#include "advee/canopen/runtime.hpp"
#include "advee/canopen/sim/drive_sim.hpp"
#include "advee/canopen/sim/lss_slave.hpp"
#include "advee/cli.hpp"

using namespace advee::canopen;

int main(int argc, char** argv) {
  CLI::App app{"advee-canopen-sim-drive: one simulated CiA 402 drive (EPOS or IclA profile) on a SocketCAN\n"
               "interface, as its own process. Prints one line per NMT or CiA 402 state change.\n"
               "Signals: SIGUSR1 injects EMCY 0x4210 and a fault, SIGUSR2 toggles heartbeat silence,\n"
               "SIGINT and SIGTERM end it. An LSS slave (CiA 305, identity = 0x1018) answers on 0x7E5;\n"
               "with --unconfigured the drive has no node-ID and boots when an LSS master gives it one.\n"
               "Exit status: 0 ended by a signal, 1 the CAN interface failed, 2 bad command line or --eds file.",
               "advee-canopen-sim-drive"};
  std::string ifname = "vcan0";
  sim::DriveSimConfig cfg;
  sim::DriveFaults faults;
  int sdo_delay_ms = 0;
  int step_ms = 1;
  unsigned node = cfg.node;
  std::string profile = "epos";
  std::vector<std::string> abort_specs;
  app.add_option("-i,--interface", ifname, "CAN interface")->capture_default_str();
  app.add_option("-n,--node", node, "node-ID")->check(CLI::Range(1u, 127u))->capture_default_str();
  bool unconfigured = false;
  app.add_flag("--unconfigured", unconfigured, "no node-ID (0xFF) until an LSS master configures one; --node is ignored");
  app.add_option("--serial", cfg.serial, "serial number in 0x1018:4, part of the LSS address (default: the node-ID)");
  app.add_option("-p,--profile", profile, "object dictionary and PDO defaults")
      ->check(CLI::IsMember({"epos", "icla"}))
      ->capture_default_str();
  app.add_option("--eds", cfg.eds_file,
                 "build the dictionary from this EDS instead of the profile's shipped one (its 0x1018 is the "
                 "identity the drive reports)");
  app.add_option("--home-switch", cfg.home_switch_position, "position of the home switch")->capture_default_str();
  app.add_option("--step-ms", step_ms, "dynamics step in ms")->check(CLI::Range(1, 1000))->capture_default_str();
  app.add_option("--sdo-delay-ms", sdo_delay_ms, "answer SDO requests this late")->check(CLI::NonNegativeNumber);
  app.add_flag("--refuse-transition-16", faults.refuse_transition_16, "quick stop active stays on enable operation");
  app.add_flag("--refuse-mode-while-halt", faults.refuse_mode_change_while_halt,
               "0x6061 ignores 0x6060 while halt is set");
  app.add_flag("--no-home-switch", faults.homing_switch_missing, "homing ends in a homing error");
  app.add_option("--sdo-abort", abort_specs,
                 "answer SDO access to the object INDEX:SUB with this abort CODE (hex: INDEX:SUB=CODE; repeatable)")
      ->type_name("IDX:SUB=CODE");
  ADVEE_CLI_PARSE(app, argc, argv);
  cfg.node = static_cast<std::uint8_t>(node);
  if (profile == "icla") {
    cfg.profile = sim::DriveProfile::kIcla;
    cfg.position_per_velocity = 1.0;
  }
  cfg.step = std::chrono::milliseconds(step_ms);
  std::map<std::pair<std::uint16_t, std::uint8_t>, SdoAbort> aborts;
  for (const auto& spec : abort_specs) {
    unsigned idx, sub, code;
    char end;
    if (std::sscanf(spec.c_str(), "%x:%x=%x%c", &idx, &sub, &code, &end) != 3 || idx > 0xFFFF || sub > 0xFF)
      return advee::cli::usage_error(app, "--sdo-abort " + spec + ": expected INDEX:SUB=CODE in hex");
    aborts[{static_cast<std::uint16_t>(idx), static_cast<std::uint8_t>(sub)}] = static_cast<SdoAbort>(code);
  }
  if (!cfg.eds_file.empty()) {
    // Checked before any I/O, like the other arguments.
    const DescriptionResult r = load_device_description(cfg.eds_file, cfg.node);
    for (const auto& e : r.errors) std::fprintf(stderr, "advee-canopen-sim-drive: %s\n", e.text().c_str());
    if (!r.description) return 2;
  }
  std::setvbuf(stdout, nullptr, _IOLBF, 0);

  try {
    EventLoop loop;
    std::unique_ptr<sim::LssSimNode> lss_node;
    CanPort port(loop, CanSocket::open(ifname), [&lss_node](const CanFrame& f) { lss_node->handle(f); });
    lss_node = std::make_unique<sim::LssSimNode>(cfg, unconfigured ? kLssUnconfigured : cfg.node, port.sender(),
                                                 system_monotonic_clock());
    // The drive exists while the node has a node-ID; LSS may build it anew.
    sim::SimulatedDrive* drive = nullptr;
    auto state = cia402::State::kNotReadyToSwitchOn;
    auto nmt = NmtState::kBootUp;
    lss_node->set_on_start([&](std::uint8_t id) {
      drive = lss_node->drive();
      if (!drive) {
        std::printf("node %u unconfigured\n", cfg.node);
        return;
      }
      cfg.node = id;
      drive->faults() = faults;
      drive->sdo().faults().response_delay = std::chrono::milliseconds(sdo_delay_ms);
      drive->sdo().faults().abort_on = aborts;
      std::printf("node %u boot\n", id);
      nmt = NmtState::kBootUp;
    });
    auto report = [&] {
      if (!drive) return;
      if (drive->nmt_state() != nmt) {
        nmt = drive->nmt_state();
        std::printf("node %u nmt %s\n", cfg.node, std::string(to_string(nmt)).c_str());
      }
      if (drive->state() != state) {
        state = drive->state();
        std::printf("node %u state %s\n", cfg.node, std::string(cia402::to_string(state)).c_str());
      }
    };
    loop.add_timer_source([&] { return lss_node->deadline(); },
                          [&] {
                            lss_node->poll();
                            report();
                          });
    SignalHandler signals(loop, {SIGINT, SIGTERM, SIGUSR1, SIGUSR2}, [&](int sig) {
      if (sig != SIGINT && sig != SIGTERM && !drive) return;
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
    lss_node->power_on();
    const auto& id = lss_node->lss().address();
    if (unconfigured)
      std::printf("node unconfigured ready on %s (%s, serial 0x%08X)\n", ifname.c_str(),
                  cfg.profile == sim::DriveProfile::kEpos ? "epos" : "icla", id.serial());
    else
      std::printf("node %u ready on %s (%s)\n", cfg.node, ifname.c_str(),
                  cfg.profile == sim::DriveProfile::kEpos ? "epos" : "icla");
    loop.run();
    if (!drive) {
      std::printf("node unconfigured exit\n");
      return 0;
    }
    std::printf("node %u exit: %llu RPDOs in, %llu TPDOs out, %llu SDO requests\n", cfg.node,
                static_cast<unsigned long long>(drive->rpdos_received()),
                static_cast<unsigned long long>(drive->tpdos_sent()),
                static_cast<unsigned long long>(drive->sdo().requests()));
  } catch (const std::exception& e) {
    std::fprintf(stderr, "advee-canopen-sim-drive: %s\n", e.what());
    return 1;
  }
  return 0;
}
