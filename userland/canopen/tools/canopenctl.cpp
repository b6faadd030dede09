// SPDX-License-Identifier: GPL-2.0
// advee-canopenctl: command-line CANopen master tool on SocketCAN. NMT commands,
// typed SDO read/write (block transfer too), a scan of the nodes that answer
// with their identity, LSS (CiA 305: fastscan, node-ID by identity), a node
// configured from its DCF or concise DCF (CiA 302-2 boot), PDO
// dump and remap, CiA 402 status and power control, live traffic and
// heartbeat monitors. Every argument is checked before the
// CAN socket is opened. Exit status (advee/cli.hpp) 0 on success and after --help and
// --version, 1 on a CANopen or I/O error (message on stderr), 2 on usage
// errors.
#include <CLI/CLI.hpp>

#include <csignal>
#include <cstdio>
#include <map>
#include <memory>
#include <string>
#include <vector>

#include "advee/canopen/axis402.hpp"
#include "advee/canopen/pdo_config.hpp"
#include "advee/canopen/runtime.hpp"
#include "advee/cli.hpp"
#include "canopenctl_dcf.hpp"
#include "canopenctl_lss.hpp"
#include "canopenctl_text.hpp"

using namespace advee::canopen;
using namespace advee::canopen::ctl;
using namespace std::chrono_literals;

namespace {

const std::vector<std::pair<std::string, NmtCommand>> kNmtNames = {
    {"start", NmtCommand::kStart},
    {"stop", NmtCommand::kStop},
    {"preop", NmtCommand::kEnterPreOperational},
    {"reset-node", NmtCommand::kResetNode},
    {"reset-comm", NmtCommand::kResetCommunication}};

// What to do, with every argument parsed and checked.
struct Command {
  std::string name;
  std::uint8_t node = 0;
  NmtCommand nmt = NmtCommand::kStart;
  std::uint16_t index = 0;
  std::uint8_t sub = 0;
  const SdoType* type = nullptr;
  std::vector<std::uint8_t> value;
  long count = -1;  // monitor, hb: frames, -1 forever
  std::pair<std::uint8_t, std::uint8_t> nodes{1, 127};  // scan
  PdoMapping pdo;  // pdo remap
  LssCommand lss;
  DcfCommand dcf;
};

struct Args {
  std::string ifname = "can0";
  int timeout_ms = 500;
  std::string nmt_cmd, node, object, type = "hex", value, nodes = "1-127";
  long count = -1;
  int block_size = SdoClient::kDefaultBlockSize;
  std::string pdo_kind, pdo_number;
  std::vector<std::string> pdo_entries;
  int pdo_type = 255;
  bool pdo_disabled = false;
  LssArgs lss;
  DcfArgs dcf;
};

// The object and type arguments of read/write and block read/write.
void describe_transfer(CLI::App& cmd, Args& a, bool write) {
  cmd.add_option("node", a.node)->required();
  cmd.add_option("object", a.object, "INDEX[:SUB], index in hex")->required();
  auto* type = cmd.add_option("type", a.type, "u8 u16 u32 u64 i8 i16 i32 i64 str hex");
  if (!write) type->capture_default_str();
  if (write) {
    type->required();
    cmd.add_option("value", a.value, "must fit the type")->required();
  }
}

// The CLI11 description of the command line; `a` receives the raw strings.
void describe(CLI::App& app, Args& a) {
  app.add_option("-i,--interface", a.ifname, "CAN interface")->capture_default_str();
  app.add_option("-t,--timeout", a.timeout_ms, "SDO timeout in ms")->check(CLI::Range(1, 600000))->capture_default_str();
  app.require_subcommand(1, 1);
  app.fallthrough();
  auto* nmt = app.add_subcommand("nmt", "NMT command to NODE or all");
  nmt->add_option("command", a.nmt_cmd, "start|stop|preop|reset-node|reset-comm")->required();
  nmt->add_option("node", a.node, "NODE (1..127) or all")->required();
  describe_transfer(*app.add_subcommand("read", "SDO upload"), a, false);
  describe_transfer(*app.add_subcommand("write", "SDO download"), a, true);
  auto* block = app.add_subcommand("block", "SDO block transfer (segmented if the node refuses block)");
  block->require_subcommand(1, 1);
  block->fallthrough();
  block->add_option("-b,--block-size", a.block_size, "segments per block on upload")
      ->check(CLI::Range(1, static_cast<int>(SdoClient::kMaxBlockSize)))
      ->capture_default_str();
  describe_transfer(*block->add_subcommand("read", "block upload"), a, false);
  describe_transfer(*block->add_subcommand("write", "block download"), a, true);
  app.add_subcommand("scan", "which nodes answer an SDO upload of 0x1000, with their identity 0x1018")
      ->add_option("nodes", a.nodes, "NODE or FIRST-LAST")
      ->capture_default_str();
  // pdo NODE dumps; pdo remap ... rewrites one PDO (the node is checked in check()).
  auto* pdo = app.add_subcommand("pdo", "dump RPDO1-4 and TPDO1-4 as the device reports them");
  pdo->add_option("node", a.node);
  pdo->fallthrough();
  auto* remap = pdo->add_subcommand("remap", "CiA 301 safe remap of one PDO, then its read-back");
  remap->add_option("node", a.node)->required();
  remap->add_option("kind", a.pdo_kind, "rpdo|tpdo")->required();
  remap->add_option("number", a.pdo_number, "1..4 (predefined COB-ID)")->required();
  remap->add_option("entries", a.pdo_entries, "INDEX:SUB/BITS ... (at most 8, 64 bits)");
  remap->add_option("--type", a.pdo_type, "transmission type")->check(CLI::Range(0, 255))->capture_default_str();
  remap->add_flag("--disabled", a.pdo_disabled, "leave the COB-ID invalid");
  for (const char* name : {"status", "enable", "disable", "quick-stop"}) {
    const char* what = std::string(name) == "status" ? "CiA 402 statusword, state and mode"
                                                     : "CiA 402 power state via SDO (fault reset included)";
    app.add_subcommand(name, what)->add_option("node", a.node)->required();
  }
  auto* monitor = app.add_subcommand("monitor", "decode bus traffic");
  monitor->add_option("count", a.count, "frames (default: until interrupted)")->check(CLI::Range(1L, 1000000000L));
  auto* hb = app.add_subcommand("hb", "heartbeats and boot-ups with the NMT state they report");
  hb->add_option("count", a.count, "heartbeats (default: until interrupted)")->check(CLI::Range(1L, 1000000000L));
  describe_lss(app, a.lss);
  describe_dcf(app, a.dcf);
}

// Throws UsageError, or FileError for a file that cannot be read or is invalid.
Command check(const std::string& name, const Args& a) {
  Command c;
  c.name = name;
  c.count = a.count;
  if (name == "nmt") {
    bool known = false;
    for (const auto& [n, cmd] : kNmtNames)
      if (a.nmt_cmd == n) c.nmt = cmd, known = true;
    if (!known) throw UsageError("unknown NMT command '" + a.nmt_cmd + "'");
    c.node = parse_node(a.node, true);
    return c;
  }
  if (name == "monitor" || name == "hb") return c;
  if (name.rfind("lss ", 0) == 0) {
    c.lss = check_lss(name, a.lss);
    return c;
  }
  if (name.rfind("dcf ", 0) == 0) {
    c.dcf = check_dcf(name, a.dcf);
    return c;
  }
  if (name == "scan") {
    c.nodes = parse_node_range(a.nodes);
    return c;
  }
  if (a.node.empty()) throw UsageError("a node-ID is required");
  c.node = parse_node(a.node);
  if (name == "pdo remap") {
    c.pdo = parse_pdo_remap(c.node, a.pdo_kind, a.pdo_number, a.pdo_entries);
    c.pdo.transmission_type = static_cast<std::uint8_t>(a.pdo_type);
    if (a.pdo_disabled) c.pdo.cob_id |= kPdoCobInvalid;
  }
  const bool write = name == "write" || name == "block write";
  if (write || name == "read" || name == "block read") {
    std::tie(c.index, c.sub) = parse_object(a.object);
    c.type = &parse_type(a.type);
  }
  if (write) c.value = encode(*c.type, a.value);
  return c;
}

// Uploads 0x1000 from every node of `nodes` at once (one SDO client each);
// a node that answers gets 0x1018:1..4 read too. Calls done with what
// answered when every transfer has ended.
void scan(Master& master, std::pair<std::uint8_t, std::uint8_t> nodes,
          std::function<void(std::map<std::uint8_t, Identity>)> done) {
  struct State {
    std::map<std::uint8_t, Identity> found;
    int pending = 0;
    std::function<void(std::map<std::uint8_t, Identity>)> done;
    void end_one() {
      if (--pending == 0) done(std::move(found));
    }
  };
  auto st = std::make_shared<State>();
  st->done = std::move(done);
  st->pending = nodes.second - nodes.first + 1;
  for (unsigned n = nodes.first; n <= nodes.second; ++n) {
    const auto node = static_cast<std::uint8_t>(n);
    SdoClient& sdo = master.sdo(node);
    sdo.read<std::uint32_t>(0x1000, 0, [st, &sdo, node](std::error_code ec, std::uint32_t type) {
      if (ec) return st->end_one();
      st->found[node].device_type = type;
      st->pending += 4;
      for (std::uint8_t sub = 1; sub <= 4; ++sub)
        sdo.read<std::uint32_t>(0x1018, sub, [st, node, sub](std::error_code ec2, std::uint32_t v) {
          if (!ec2) st->found[node].identity[sub - 1] = v;
          st->end_one();
        });
      st->end_one();
    });
  }
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{"advee-canopenctl: a CANopen master tool on SocketCAN (docs/canopen.md).\n"
               "Exit status 0, 1 on a CANopen or I/O error, 2 on a usage error.",
               "advee-canopenctl"};
  Args a;
  describe(app, a);
  ADVEE_CLI_PARSE(app, argc, argv);
  Command command;
  try {
    const CLI::App* sub = app.get_subcommands().front();
    std::string name = sub->get_name();
    if (!sub->get_subcommands().empty()) name += " " + sub->get_subcommands().front()->get_name();
    command = check(name, a);
  } catch (const UsageError& e) {
    return advee::cli::usage_error(app, e.what());
  } catch (const FileError& e) {
    std::fprintf(stderr, "advee-canopenctl: %s\n", e.what());
    return advee::cli::kExitFailure;
  }
  const Command& c = command;
  const std::string& cmd = c.name;
  if (cmd == "dcf concise") return write_concise(c.dcf);  // no bus

  int rc = 0;
  try {
    EventLoop loop;
    MasterConfig mc;
    mc.sdo_timeout = std::chrono::milliseconds(a.timeout_ms);
    MasterRuntime rt(loop, a.ifname, mc);
    Master& master = rt.master();
    auto fail = [&](const std::string& what, std::error_code ec) {
      std::fprintf(stderr, "advee-canopenctl: %s: %s\n", what.c_str(), ec.message().c_str());
      rc = 1;
      loop.stop();
    };
    SignalHandler signals(loop, {SIGINT, SIGTERM}, [&](int) { loop.stop(); });

    std::unique_ptr<Axis402> axis;
    struct StatusPoller final : TimedService {
      Master& m;
      std::function<void()> fn;
      TimePoint next;
      StatusPoller(Master& mm, std::function<void()> f) : m(mm), fn(std::move(f)), next(mm.now()) { reg_ = m.attach(*this); }
      Registration reg_;
      void poll() override {
        if (m.now() < next) return;
        next = TimePoint::max();
        fn();
      }
      std::optional<TimePoint> deadline() const override {
        if (next == TimePoint::max()) return std::nullopt;
        return next;
      }
    };
    std::unique_ptr<StatusPoller> poller;
    std::unique_ptr<LssMaster> lss;
    std::unique_ptr<NodeBoot> dcf_boot;

    const std::uint8_t node = c.node;
    if (cmd == "nmt") {
      master.nmt(c.nmt, node);
      loop.post([&] { loop.stop(); });
    } else if (cmd == "read" || cmd == "write" || cmd == "block read" || cmd == "block write") {
      // A read prints the value; either ends the tool.
      auto done = [&](const SdoResult& r) {
        if (!r.ok()) return fail(cmd, r.error());
        if (cmd == "read" || cmd == "block read")
          std::printf("%s\n", format(*c.type, r.data).c_str());
        loop.stop();
      };
      SdoClient& sdo = master.sdo(node);
      sdo.set_block_size(static_cast<std::uint8_t>(a.block_size));
      if (cmd == "read") sdo.upload(c.index, c.sub, done);
      if (cmd == "write") sdo.download(c.index, c.sub, c.value, done);
      if (cmd == "block read") sdo.block_upload(c.index, c.sub, done);
      if (cmd == "block write") sdo.block_download(c.index, c.sub, c.value, done);
    } else if (cmd == "scan") {
      scan(master, c.nodes, [&](std::map<std::uint8_t, Identity> found) {
        for (const auto& [n, id] : found) std::printf("%s\n", describe_identity(n, id).c_str());
        if (found.empty()) std::fprintf(stderr, "advee-canopenctl: scan: no node answered\n"), rc = 1;
        loop.stop();
      });
    } else if (cmd == "pdo") {
      auto remaining = std::make_shared<int>(8);
      for (PdoKind kind : {PdoKind::kRpdo, PdoKind::kTpdo})
        for (unsigned n = 1; n <= 4; ++n)
          read_pdo_mapping(master.sdo(node), kind, n, [&, kind, n, remaining](std::error_code ec, const PdoMapping& m) {
            if (ec)
              std::printf("%s%u: %s\n", kind == PdoKind::kRpdo ? "RPDO" : "TPDO", n, ec.message().c_str()), rc = 1;
            else
              std::printf("%s\n", to_string(m).c_str());
            if (--*remaining == 0) loop.stop();
          });
    } else if (cmd == "pdo remap") {
      run_sdo_writes(master.sdo(node), pdo_remap_writes(c.pdo), [&, node](const SdoSequenceResult& r) {
        if (r.error) {
          char what[48];
          std::snprintf(what, sizeof what, "pdo remap: write %04X:%02X", r.failed.index, r.failed.sub);
          return fail(what, r.error);
        }
        read_pdo_mapping(master.sdo(node), c.pdo.kind, c.pdo.number, [&](std::error_code ec, const PdoMapping& m) {
          if (ec) return fail("pdo remap: read-back", ec);
          std::printf("%s\n", to_string(m).c_str());
          if (to_string(m) != to_string(c.pdo))
            std::fprintf(stderr, "advee-canopenctl: pdo remap: the device reports another mapping than %s\n",
                         to_string(c.pdo).c_str()), rc = 1;
          loop.stop();
        });
      });
    } else if (cmd == "status") {
      master.sdo(node).read<std::uint16_t>(0x6041, 0, [&, node](std::error_code ec, std::uint16_t sw) {
        if (ec) return fail("statusword", ec);
        master.sdo(node).read<std::int8_t>(0x6061, 0, [&, sw](std::error_code ec2, std::int8_t mode) {
          if (ec2) return fail("modes of operation display", ec2);
          std::printf("statusword 0x%04X: %s%s%s, mode %d\n", sw, std::string(cia402::to_string(cia402::decode(sw))).c_str(),
                      (sw & cia402::sw::kTargetReached) ? ", target reached" : "",
                      (sw & cia402::sw::kWarning) ? ", warning" : "", mode);
          loop.stop();
        });
      });
    } else if (cmd == "enable" || cmd == "disable" || cmd == "quick-stop") {
      const cia402::State target = cmd == "enable"    ? cia402::State::kOperationEnabled
                                   : cmd == "disable" ? cia402::State::kSwitchOnDisabled
                                                      : cia402::State::kQuickStopActive;
      // SDO both ways: a tool must not depend on the device's PDO setup.
      axis = std::make_unique<Axis402>(AxisConfig{1s, false}, [&master] { return master.now(); },
                                       [&master, node](std::uint16_t w) { master.sdo(node).write<std::uint16_t>(0x6040, 0, w, nullptr); });
      std::function<void()> read_status;
      read_status = [&, node] {
        master.sdo(node).read<std::uint16_t>(0x6041, 0, [&](std::error_code ec, std::uint16_t sw) {
          if (ec) return fail("statusword", ec);
          const bool first = !axis->has_statusword();
          axis->on_statusword(sw);
          if (first)
            axis->request(target, [&](std::error_code e) {
              if (e) return fail(cmd, e);
              std::printf("%s\n", std::string(cia402::to_string(axis->state())).c_str());
              loop.stop();
            });
          poller->next = master.now() + 10ms;
        });
      };
      poller = std::make_unique<StatusPoller>(master, read_status);
    } else if (cmd == "dcf download") {
      dcf_boot = run_dcf_download(master, c.dcf, [&](int status) {
        rc = status;
        loop.stop();
      });
    } else if (cmd.rfind("lss ", 0) == 0) {
      lss = run_lss(master, c.lss, [&](int status) {
        rc = status;
        loop.stop();
      });
    } else if (cmd == "hb" || cmd == "monitor") {
      // count lines, then nothing: frames of the batch that ends the count
      // are still delivered after loop.stop().
      long count = c.count;
      master.set_observer([&](const CanFrame& f) {
        const auto line = cmd == "hb" ? describe_heartbeat(f) : describe_frame(f);
        if (!line || count == 0) return;
        std::printf("%s\n", line->c_str());
        std::fflush(stdout);
        if (count > 0 && --count == 0) loop.stop();
      });
    }
    loop.run();
  } catch (const std::exception& e) {
    std::fprintf(stderr, "advee-canopenctl: %s\n", e.what());
    return advee::cli::kExitFailure;
  }
  return rc;
}
