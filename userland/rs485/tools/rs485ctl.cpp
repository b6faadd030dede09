// SPDX-License-Identifier: GPL-2.0
// advee-rs485ctl: look at and talk to an RS-485/EIA-422 bus run by n_rs485.
// Subcommands: scan, xfer (raw), reset, reset-node, stats, watch, config.
// Exit status: 0 ok, 1 protocol outcome not OK, 2 usage, 3 device/system error.
#include <poll.h>
#include <unistd.h>

#include <CLI/CLI.hpp>
#include <chrono>
#include <csignal>
#include <cstdio>
#include <ctime>
#include <iostream>
#include <memory>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>

#include "advee/cli.hpp"
#include "advee/rs485/bus.hpp"
#include "advee/rs485/devices/device.hpp"
#include "advee/signal_fd.hpp"
#include "advee/unique_fd.hpp"
#include "cli_parse.hpp"

namespace {

using namespace advee::rs485;
using advee::rs485::cli::UsageError;
using json = nlohmann::json;

// advee/cli.hpp: 1 for every runtime failure, the protocol's and the system's.
constexpr int kExitOk = advee::cli::kExitSuccess;
constexpr int kExitOutcome = advee::cli::kExitFailure;
constexpr int kExitUsage = advee::cli::kExitUsage;
constexpr int kExitSystem = advee::cli::kExitFailure;

constexpr const char* kExitCodes =
    "EXIT STATUS\n"
    "  0  success (every transaction OK; for scan: the scan ran)\n"
    "  1  a transaction ended with a protocol outcome other than OK\n"
    "     (TIMEOUT, BADCRC, UNKINSTR, DEVERR, ERROR, BADRESP), or a device or\n"
    "     system error (cannot open the bus, discipline missing, hangup, an\n"
    "     ioctl failed); the message on stderr says which\n"
    "  2  usage error (bad option, address, data or duration)\n";

struct Global {
  std::string bus;
  std::optional<int> ldisc;
  bool json = false;
};

std::string hex8(unsigned v) {
  char b[8];
  std::snprintf(b, sizeof(b), "0x%02x", v & 0xFF);
  return b;
}

std::unique_ptr<Bus> open_bus(const Global& g) {
  if (g.bus.empty()) throw UsageError("no bus given: use --bus DEVICE (e.g. /dev/ttyTSU0 or a)");
  BusOptions o;
  o.ldisc = g.ldisc;
  return std::make_unique<Bus>(g.bus, o);
}

CallOptions call_options(const std::string& timeout, const std::string& retries) {
  CallOptions o;
  if (!timeout.empty()) o.timeout = cli::parse_duration(timeout);
  if (!retries.empty()) o.retries = static_cast<unsigned>(cli::parse_uint(retries, 0, 16, "retries"));
  return o;
}

std::string outcome_text(const std::error_code& ec) {
  if (!ec) return "OK";
  if (ec.category() == rs485_category()) return std::string(outcome_name(static_cast<Outcome>(ec.value())));
  return "SYSTEM: " + ec.message();
}

json flags_json(std::uint8_t f) {
  json j = json::array();
  if (f & response_flag::kAck) j.push_back("ACK");
  if (f & response_flag::kUnknownInstruction) j.push_back("UNKINSTR");
  if (f & response_flag::kDeviceError) j.push_back("DEVERR");
  if (f & response_flag::kEvent) j.push_back("EVENT");
  return j;
}

std::string flags_text(std::uint8_t f) {
  std::string s;
  for (const auto& name : flags_json(f)) s += (s.empty() ? "" : "|") + name.get<std::string>();
  return hex8(f) + (s.empty() ? "" : " (" + s + ")");
}

// --- scan ---
struct ScanArgs {
  std::string first = "0x00", last = "0xfe", timeout = "10ms";
};

int run_scan(const Global& g, const ScanArgs& a) {
  const auto first = cli::parse_address(a.first), last = cli::parse_address(a.last);
  if (first > last) throw UsageError("scan: --first is above --last");
  const CallOptions opts(cli::parse_duration(a.timeout), 0u);
  auto bus = open_bus(g);
  json found = json::array();
  std::map<unsigned, std::string> cell;  // address -> what the grid shows
  for (unsigned addr = first; addr <= last; ++addr) {
    auto r = bus->transact(Request(static_cast<std::uint8_t>(addr), standard_instr::kGetFirmwareVersion, {}, opts));
    if (r.error && !is_protocol_outcome(r.error))
      throw std::system_error(r.error, "scan: address " + hex8(addr));
    if (r.error == Outcome::timeout) continue;
    json d{{"addr", addr}, {"outcome", outcome_text(r.error)}};
    if (auto v = decode_firmware_version(r.data); !r.error && v) {
      d["firmware"] = {{"major", v->major}, {"minor", v->minor}};
      cell[addr] = hex8(addr).substr(2);
    } else {
      // Something answered, but not a firmware version: BADCRC, UNKINSTR, ...
      if (!r.error) d["outcome"] = "BADRESP";
      cell[addr] = "??";
    }
    found.push_back(d);
  }
  if (g.json) {
    std::cout << json{{"bus", bus->device()}, {"first", first}, {"last", last}, {"devices", found}}.dump(2) << "\n";
    return kExitOk;
  }
  std::printf("     0  1  2  3  4  5  6  7  8  9  a  b  c  d  e  f\n");
  for (unsigned row = 0; row < 0x100; row += 16) {
    std::printf("%02x:", row);
    for (unsigned col = 0; col < 16; ++col) {
      const unsigned addr = row + col;
      if (addr < first || addr > last || addr == kBroadcast)
        std::printf("   ");
      else
        std::printf(" %s", cell.count(addr) ? cell[addr].c_str() : "--");
    }
    std::printf("\n");
  }
  for (const auto& d : found) {
    std::printf("%s: ", hex8(d["addr"].get<unsigned>()).c_str());
    if (d.contains("firmware"))
      std::printf("firmware %u.%u\n", d["firmware"]["major"].get<unsigned>(), d["firmware"]["minor"].get<unsigned>());
    else
      std::printf("answered %s\n", d["outcome"].get<std::string>().c_str());
  }
  return kExitOk;
}

// --- xfer ---
struct XferArgs {
  std::string addr, instr, timeout, retries;
  std::vector<std::string> data;
  bool noack = false;
};

int run_xfer(const Global& g, const XferArgs& a) {
  Request req(cli::parse_address(a.addr, true), static_cast<std::uint8_t>(cli::parse_uint(a.instr, 0, 255, "instruction")),
              cli::parse_hex_bytes(a.data), call_options(a.timeout, a.retries));
  req.no_ack = a.noack;
  auto bus = open_bus(g);
  const auto r = bus->transact(req);
  if (r.error && !is_protocol_outcome(r.error)) throw std::system_error(r.error, "xfer");
  if (g.json) {
    std::cout << json{{"addr", req.addr},       {"instr", req.instr},
                      {"outcome", outcome_text(r.error)}, {"flags", r.flags},
                      {"flag_names", flags_json(r.flags)}, {"attempts", r.attempts},
                      {"data", r.data}}
                     .dump(2)
              << "\n";
  } else {
    std::printf("outcome:  %s\n", outcome_text(r.error).c_str());
    std::printf("flags:    %s\n", flags_text(r.flags).c_str());
    std::printf("attempts: %u\n", r.attempts);
    std::printf("data:     [%zu] %s\n", r.data.size(), cli::hex(r.data).c_str());
  }
  return r.error ? kExitOutcome : kExitOk;
}

// --- reset (RESET instruction) ---
int run_reset(const Global& g, const std::string& target, const std::string& timeout) {
  const bool all = target == "all" || target == "broadcast";
  const std::uint8_t addr = all ? kBroadcast : cli::parse_address(target, true);
  const CallOptions opts = call_options(timeout, "");
  auto bus = open_bus(g);
  const auto r = bus->transact(Request(addr, standard_instr::kReset, {}, opts));
  if (r.error && !is_protocol_outcome(r.error)) throw std::system_error(r.error, "reset");
  if (g.json)
    std::cout << json{{"addr", addr}, {"outcome", outcome_text(r.error)}}.dump() << "\n";
  else
    std::printf("%s: RESET %s\n", addr == kBroadcast ? "broadcast" : hex8(addr).c_str(), outcome_text(r.error).c_str());
  return r.error ? kExitOutcome : kExitOk;
}

// --- reset-node (error counter) ---
int run_reset_node(const Global& g, const std::string& target) {
  const auto addr = cli::parse_address(target);
  auto bus = open_bus(g);
  bus->reset_node(addr);
  const auto n = bus->node(addr);
  if (g.json)
    std::cout << json{{"addr", addr}, {"state", node_state_name(n.state)}, {"errors", n.errors}}.dump() << "\n";
  else
    std::printf("%s: error counter reset (%s, %u)\n", hex8(addr).c_str(), std::string(node_state_name(n.state)).c_str(),
                n.errors);
  return kExitOk;
}

// --- stats ---
struct StatsArgs {
  std::vector<std::string> nodes;
  bool all_nodes = false;
};

int run_stats(const Global& g, const StatsArgs& a) {
  std::vector<std::uint8_t> wanted;
  for (const auto& n : a.nodes) wanted.push_back(cli::parse_address(n));
  auto bus = open_bus(g);
  const auto s = bus->stats();
  const std::pair<const char*, std::uint64_t> rows[] = {
      {"tx_frames", s.tx_frames},   {"tx_bytes", s.tx_bytes},         {"rx_frames", s.rx_frames},
      {"rx_bytes", s.rx_bytes},     {"rx_crc_errors", s.rx_crc_errors}, {"rx_truncated", s.rx_truncated},
      {"rx_noise", s.rx_noise},     {"rx_overruns", s.rx_overruns},   {"rx_framing", s.rx_framing},
      {"xfers", s.xfers},           {"xfers_ok", s.xfers_ok},         {"xfers_failed", s.xfers_failed},
      {"timeouts", s.timeouts},     {"retries", s.retries},           {"events", s.events},
      {"events_dropped", s.events_dropped}, {"unexpected", s.unexpected}};
  // Nodes: the ones asked for, else every node with a non-zero counter.
  std::vector<NodeStatus> nodes;
  if (!wanted.empty()) {
    for (auto addr : wanted) nodes.push_back(bus->node(addr));
  } else {
    for (unsigned addr = 0; addr <= kMaxNodeAddress; ++addr) {
      auto n = bus->node(static_cast<std::uint8_t>(addr));
      if (a.all_nodes || n.errors) nodes.push_back(n);
    }
  }
  if (g.json) {
    json j{{"bus", bus->device()}, {"stats", json::object()}, {"nodes", json::array()}};
    for (auto [name, v] : rows) j["stats"][name] = v;
    for (const auto& n : nodes)
      j["nodes"].push_back({{"addr", n.addr}, {"state", node_state_name(n.state)}, {"errors", n.errors}});
    std::cout << j.dump(2) << "\n";
    return kExitOk;
  }
  std::printf("bus %s\n", bus->device().c_str());
  for (auto [name, v] : rows) std::printf("  %-16s %llu\n", name, static_cast<unsigned long long>(v));
  if (nodes.empty()) {
    std::printf("nodes: every error counter is 0\n");
  } else {
    std::printf("node  state    errors\n");
    for (const auto& n : nodes)
      std::printf("%s  %-8s %u\n", hex8(n.addr).c_str(), std::string(node_state_name(n.state)).c_str(), n.errors);
  }
  return kExitOk;
}

// --- watch ---
struct WatchArgs {
  std::uint64_t count = 0;
  std::string timeout, addr;
};

int run_watch(const Global& g, const WatchArgs& a) {
  std::optional<std::uint8_t> only;
  if (!a.addr.empty()) only = cli::parse_address(a.addr);
  std::optional<std::chrono::steady_clock::time_point> deadline;
  if (!a.timeout.empty()) deadline = std::chrono::steady_clock::now() + cli::parse_duration(a.timeout);
  auto bus = open_bus(g);

  // SIGINT/SIGTERM through a signalfd, so that poll() sees Ctrl-C.
  const advee::SignalFd sfd({SIGINT, SIGTERM});

  std::uint64_t seen = 0;
  for (;;) {
    int wait_ms = -1;
    if (deadline) {
      const auto left = std::chrono::duration_cast<std::chrono::milliseconds>(*deadline - std::chrono::steady_clock::now());
      if (left.count() <= 0) break;
      wait_ms = static_cast<int>(std::min<std::int64_t>(left.count() + 1, 1 << 30));
    }
    pollfd fds[2] = {{bus->event_fd(), POLLIN, 0}, {sfd.fd(), POLLIN, 0}};
    if (::poll(fds, 2, wait_ms) < 0) {
      if (errno == EINTR) continue;
      throw std::system_error(errno, std::system_category(), "poll");
    }
    if (fds[1].revents) break;
    if (!fds[0].revents) continue;
    bool got = false;
    while (auto f = bus->read_event()) {  // throws on hangup
      got = true;
      if (only && f->addr != *only) continue;
      const double t = std::chrono::duration<double>(std::chrono::system_clock::now().time_since_epoch()).count();
      if (g.json) {
        std::cout << json{{"time", t}, {"addr", f->addr}, {"instr", f->instr}, {"flags", f->flags},
                          {"flag_names", flags_json(f->flags)}, {"data", f->data}}
                         .dump()
                  << std::endl;
      } else {
        std::printf("%.6f %s instr %s flags %s data [%zu] %s\n", t, hex8(f->addr).c_str(), hex8(f->instr).c_str(),
                    flags_text(f->flags).c_str(), f->data.size(), cli::hex(f->data).c_str());
        std::fflush(stdout);
      }
      if (a.count && ++seen >= a.count) return kExitOk;
    }
    // POLLHUP/POLLERR without a frame: the line is gone.
    if (!got && (fds[0].revents & (POLLHUP | POLLERR)))
      throw std::system_error(std::make_error_code(std::errc::io_error), bus->device() + ": hung up");
  }
  return kExitOk;
}

// --- config ---
struct ConfigArgs {
  std::string baud, timeout, retries, gap;
};

void print_config(const Global& g, const Bus& bus, const BusConfig& c) {
  if (g.json) {
    std::cout << json{{"bus", bus.device()}, {"baud", c.baud}, {"timeout_us", c.timeout.count()}, {"retries", c.retries},
                      {"gap_chars", c.gap_chars}}
                     .dump(2)
              << "\n";
  } else {
    std::printf("bus       %s\nbaud      %u\ntimeout   %lld us\nretries   %u\ngap_chars %u\n", bus.device().c_str(), c.baud,
                static_cast<long long>(c.timeout.count()), c.retries, c.gap_chars);
  }
}

int run_config_get(const Global& g) {
  auto bus = open_bus(g);
  print_config(g, *bus, bus->config());
  return kExitOk;
}

int run_config_set(const Global& g, const ConfigArgs& a) {
  if (a.baud.empty() && a.timeout.empty() && a.retries.empty() && a.gap.empty())
    throw UsageError("config set: nothing to set (--baud, --timeout, --retries, --gap)");
  std::optional<std::uint32_t> baud, retries, gap;
  std::optional<std::chrono::microseconds> timeout;
  if (!a.baud.empty()) baud = static_cast<std::uint32_t>(cli::parse_uint(a.baud, 300, 4000000, "baud"));
  if (!a.retries.empty()) retries = static_cast<std::uint32_t>(cli::parse_uint(a.retries, 0, 16, "retries"));
  if (!a.gap.empty()) gap = static_cast<std::uint32_t>(cli::parse_uint(a.gap, 2, 255, "gap"));
  if (!a.timeout.empty()) {
    timeout = cli::parse_duration(a.timeout);
    if (*timeout < std::chrono::microseconds(100) || *timeout > std::chrono::seconds(10))
      throw UsageError("timeout " + a.timeout + " is out of range 100us..10s");
  }
  auto bus = open_bus(g);
  auto c = bus->config();
  if (baud) c.baud = *baud;
  if (retries) c.retries = *retries;
  if (gap) c.gap_chars = *gap;
  if (timeout) c.timeout = *timeout;
  bus->set_config(c);
  print_config(g, *bus, bus->config());
  return kExitOk;
}

// Man-page layout for a subcommand: the one-line summary in the command
// list, the full text and the exit codes below its options.
void details(CLI::App* cmd, const std::string& text) {
  std::string indented = "  ";
  for (char c : text) {
    indented += c;
    if (c == '\n') indented += "  ";
  }
  cmd->footer("\nDESCRIPTION\n" + indented + "\n\n" + kExitCodes);
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{
      "advee-rs485ctl - inspect and drive an RS-485/EIA-422 bus run by the n_rs485 line discipline.\n\n"
      "The bus is a tty (/dev/ttyTSU0, /dev/ttyS1, ...) or a bus name (a, b, power = /dev/rs485/NAME).\n"
      "The discipline is attached if it is not yet (number from /sys/module/n_rs485/parameters/ldisc,\n"
      "else 29). Addresses and numbers are decimal or 0x hex; durations take a unit (us, ms, s;\n"
      "default ms). Transactions go through the kernel's queue, so advee-rs485ctl can run next to the\n"
      "robot's drivers.",
      "advee-rs485ctl"};
  app.footer(std::string("\n") + kExitCodes +
             "\nEXAMPLES\n"
             "  advee-rs485ctl -b /dev/ttyTSU0 scan\n"
             "  advee-rs485ctl -b a xfer 0x10 0x10                 # GET_BOTH of the SD1 at 0x10\n"
             "  advee-rs485ctl -b power xfer 0x01 0x02 ff 01       # PSC1: switch channel 0 on\n"
             "  advee-rs485ctl -b power --json watch --count 5\n"
             "  advee-rs485ctl -b a config set --timeout 20ms\n");
  app.require_subcommand(1);
  Global g;
  app.add_option("-b,--bus", g.bus, "Bus device: a tty path or a name under /dev/rs485/")->type_name("DEVICE")->envname("RS485_BUS");
  app.add_option("--ldisc", g.ldisc, "Line discipline number to attach (default: the module's, else 29)")
      ->check(CLI::Range(1, 255));
  app.add_flag("-j,--json", g.json, "Machine-readable JSON output");

  ScanArgs scan;
  auto* scan_cmd = app.add_subcommand("scan", "Find the nodes on the bus (GET_FW_VERSION to every address)");
  details(scan_cmd,
      "Sends GET_FW_VERSION to every address from --first to --last (default 0x00..0xfe) with a short\n"
      "timeout and no retries, like i2cdetect. The grid shows the address of a node that answered with\n"
      "a firmware version, '?\?' for one that answered otherwise (UNKINSTR, DEVERR, BADCRC, ERROR), '--'\n"
      "for silence. Each silent address costs one timeout and counts +8 on that address's error\n"
      "counter in the kernel (see 'stats'). Exit 0 when the scan ran, whatever it found.");
  scan_cmd->add_option("--first", scan.first, "First address (default 0x00)")->type_name("ADDR");
  scan_cmd->add_option("--last", scan.last, "Last address (default 0xfe)")->type_name("ADDR");
  scan_cmd->add_option("-t,--timeout", scan.timeout, "Response timeout per address (default 10ms)")->type_name("DURATION");

  XferArgs xfer;
  auto* xfer_cmd = app.add_subcommand("xfer", "Send one instruction and print the response");
  xfer_cmd->alias("raw");
  details(xfer_cmd,
      "Sends INSTR with the hex DATA bytes to ADDR and prints the outcome (OK, TIMEOUT, BADCRC,\n"
      "UNKINSTR, DEVERR, ERROR), the response flags, the number of attempts and the response data.\n"
      "ADDR 0xff broadcasts (no response; OK once sent). DATA: '01 02', '0102', '0x01,0x02' or 'de:ad'.\n"
      "Exit 0 if the outcome is OK, 1 otherwise.");
  xfer_cmd->add_option("addr", xfer.addr, "Node address 0x00..0xfe, or 0xff (broadcast)")->type_name("ADDR")->required();
  xfer_cmd->add_option("instr", xfer.instr, "Instruction 0x00..0xff")->type_name("INSTR")->required();
  xfer_cmd->add_option("data", xfer.data, "Request data bytes in hex")->type_name("DATA");
  xfer_cmd->add_option("-t,--timeout", xfer.timeout, "Response timeout (default: the bus's)")->type_name("DURATION");
  xfer_cmd->add_option("-r,--retries", xfer.retries, "Retries after a failure, 0..16 (default: the bus's)")->type_name("N");
  xfer_cmd->add_flag("--noack", xfer.noack, "Set NOACK: the node executes and does not answer");

  std::string reset_target, reset_timeout;
  auto* reset_cmd = app.add_subcommand("reset", "Send RESET to a node, or to every node");
  details(reset_cmd,
      "Sends the standard RESET instruction (0xff). To one ADDR the node ACKs and then resets; with\n"
      "'all' (or 0xff) it is broadcast: every device resets, nothing answers.");
  reset_cmd->add_option("target", reset_target, "Node address, or 'all'")->type_name("ADDR|all")->required();
  reset_cmd->add_option("-t,--timeout", reset_timeout, "Response timeout (default: the bus's)")->type_name("DURATION");

  std::string reset_node_target;
  auto* reset_node_cmd = app.add_subcommand("reset-node", "Reset a node's error counter to 0 (error-active)");
  details(reset_node_cmd,
      "Sets the kernel's CAN-like error counter of ADDR back to 0, so that a node that went\n"
      "error-passive (128) or off (256) is polled again by the drivers. Sends nothing on the bus.");
  reset_node_cmd->add_option("addr", reset_node_target, "Node address 0x00..0xfe")->type_name("ADDR")->required();

  StatsArgs stats;
  auto* stats_cmd = app.add_subcommand("stats", "Show bus statistics and node error states");
  details(stats_cmd,
      "Prints the discipline's counters since attach (frames, bytes, CRC errors, timeouts, retries,\n"
      "events, ...) and the error state of the nodes: by default every node whose counter is not 0,\n"
      "with --node only those, with --all-nodes all 255. States: active (< 128), passive (< 256), off.");
  stats_cmd->add_option("-n,--node", stats.nodes, "Show this node (repeatable)")->type_name("ADDR");
  stats_cmd->add_flag("--all-nodes", stats.all_nodes, "Show every node, also those without errors");

  WatchArgs watch;
  auto* watch_cmd = app.add_subcommand("watch", "Print event frames as they arrive");
  details(watch_cmd,
      "Prints every frame the discipline queues for reading: EVENT frames (PSC1 PAUSE/POWER) and\n"
      "responses no transaction waited for, until Ctrl-C, --count frames or --timeout. One line per\n"
      "frame (time, address, instruction, flags, data); with --json one JSON object per line.\n"
      "Only one reader gets each frame: do not run it next to a driver that reads events.");
  watch_cmd->add_option("-c,--count", watch.count, "Stop after this many frames")->type_name("N");
  watch_cmd->add_option("-t,--timeout", watch.timeout, "Stop after this time")->type_name("DURATION");
  watch_cmd->add_option("-a,--addr", watch.addr, "Only frames from this address")->type_name("ADDR");

  ConfigArgs cfg;
  auto* config_cmd = app.add_subcommand("config", "Get or set the bus configuration");
  details(config_cmd,
      "'config' or 'config get' prints the line rate, default response timeout, default retries and\n"
      "inter-frame gap; 'config set' changes the given ones (the kernel checks the ranges: baud\n"
      "300..4000000, timeout 100us..10s, retries 0..16, gap 2..255 characters). The settings stay\n"
      "until the discipline is detached.");
  config_cmd->require_subcommand(0, 1);
  auto* config_get = config_cmd->add_subcommand("get", "Print the configuration");
  auto* config_set = config_cmd->add_subcommand("set", "Change the configuration");
  config_set->add_option("--baud", cfg.baud, "Line rate in Bd (300..4000000)")->type_name("N");
  config_set->add_option("--timeout", cfg.timeout, "Default response timeout (100us..10s)")->type_name("DURATION");
  config_set->add_option("--retries", cfg.retries, "Default retries after a failure (0..16)")->type_name("N");
  config_set->add_option("--gap", cfg.gap, "Idle characters before a request (2..255)")->type_name("N");
  config_set->footer(kExitCodes);
  config_get->footer(kExitCodes);

  ADVEE_CLI_PARSE(app, argc, argv);

  try {
    if (*scan_cmd) return run_scan(g, scan);
    if (*xfer_cmd) return run_xfer(g, xfer);
    if (*reset_cmd) return run_reset(g, reset_target, reset_timeout);
    if (*reset_node_cmd) return run_reset_node(g, reset_node_target);
    if (*stats_cmd) return run_stats(g, stats);
    if (*watch_cmd) return run_watch(g, watch);
    if (*config_cmd) return *config_set ? run_config_set(g, cfg) : run_config_get(g);
    (void)config_get;
  } catch (const UsageError& e) {
    std::fprintf(stderr, "advee-rs485ctl: %s\nTry 'advee-rs485ctl --help'.\n", e.what());
    return kExitUsage;
  } catch (const std::system_error& e) {
    std::fprintf(stderr, "advee-rs485ctl: %s\n", e.what());
    return kExitSystem;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "advee-rs485ctl: %s\n", e.what());
    return kExitSystem;
  }
  return kExitUsage;
}
