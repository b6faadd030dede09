// SPDX-License-Identifier: GPL-2.0
// canopenctl: command-line CANopen master tool on SocketCAN. NMT commands,
// typed SDO read/write, PDO mapping dump, CiA 402 status and power control,
// live traffic monitor. Exit status 0 on success, 1 on a CANopen error
// (message on stderr), 2 on usage errors.
#include <getopt.h>

#include <cerrno>
#include <cinttypes>
#include <csignal>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <string>
#include <vector>

#include "advee/byte_order.hpp"
#include "advee/canopen/axis402.hpp"
#include "advee/canopen/pdo_config.hpp"
#include "advee/canopen/runtime.hpp"

using namespace advee::canopen;
using advee::load_le;
using advee::store_le;
using namespace std::chrono_literals;

namespace {

[[noreturn]] void usage_error(const char* fmt, const char* arg = "") {
  std::fprintf(stderr, "canopenctl: ");
  std::fprintf(stderr, fmt, arg);
  std::fprintf(stderr, "\nTry 'canopenctl --help'.\n");
  std::exit(2);
}

void usage(FILE* out) {
  std::fputs(
      "usage: canopenctl [-i IF] [-t MS] COMMAND [ARGS]\n"
      "commands:\n"
      "  nmt start|stop|preop|reset-node|reset-comm NODE|all\n"
      "  read NODE INDEX[:SUB] [TYPE]         SDO upload (TYPE default hex)\n"
      "  write NODE INDEX[:SUB] TYPE VALUE    SDO download\n"
      "  pdo NODE                             dump RPDO1-4 and TPDO1-4 as the device reports them\n"
      "  status NODE                          CiA 402 statusword, state and mode\n"
      "  enable|disable|quick-stop NODE       CiA 402 power state via SDO (fault reset included)\n"
      "  monitor [COUNT]                      decode bus traffic (COUNT frames, default forever)\n"
      "types: u8 u16 u32 u64 i8 i16 i32 i64 str hex\n"
      "options:\n"
      "  -i, --interface IF   CAN interface (default can0)\n"
      "  -t, --timeout MS     SDO timeout (default 500)\n"
      "  -h, --help\n",
      out);
}

std::uint8_t parse_node(const char* s, bool allow_all = false) {
  if (allow_all && !std::strcmp(s, "all")) return 0;
  char* end;
  const long n = std::strtol(s, &end, 0);
  if (*end || n < 1 || n > 127) usage_error("bad node-ID '%s' (1..127)", s);
  return static_cast<std::uint8_t>(n);
}

std::pair<std::uint16_t, std::uint8_t> parse_object(const char* s) {
  char* end;
  const unsigned long idx = std::strtoul(s, &end, 16);
  unsigned long sub = 0;
  if (*end == ':') sub = std::strtoul(end + 1, &end, 0);
  if (*end || idx > 0xFFFF || sub > 0xFF) usage_error("bad object '%s' (INDEX[:SUB], index in hex)", s);
  return {static_cast<std::uint16_t>(idx), static_cast<std::uint8_t>(sub)};
}

struct TypeInfo {
  const char* name;
  int size;  // 0: variable
  bool is_signed;
};
constexpr TypeInfo kTypes[] = {{"u8", 1, false},  {"u16", 2, false}, {"u32", 4, false}, {"u64", 8, false},
                               {"i8", 1, true},   {"i16", 2, true},  {"i32", 4, true},  {"i64", 8, true},
                               {"str", 0, false}, {"hex", 0, false}};

const TypeInfo& parse_type(const char* s) {
  for (const auto& t : kTypes)
    if (!std::strcmp(t.name, s)) return t;
  usage_error("unknown type '%s'", s);
}

std::vector<std::uint8_t> encode(const TypeInfo& t, const char* v) {
  if (!std::strcmp(t.name, "str")) return {v, v + std::strlen(v)};
  if (!std::strcmp(t.name, "hex")) {
    std::vector<std::uint8_t> out;
    for (std::size_t i = 0; v[i] && v[i + 1]; i += 2) out.push_back(static_cast<std::uint8_t>(std::stoul(std::string(v + i, 2), nullptr, 16)));
    return out;
  }
  errno = 0;
  char* end;
  const long long x = t.is_signed ? std::strtoll(v, &end, 0) : static_cast<long long>(std::strtoull(v, &end, 0));
  if (*end || errno) usage_error("bad value '%s'", v);
  std::vector<std::uint8_t> out(static_cast<std::size_t>(t.size));
  store_le<std::uint64_t>(out, static_cast<std::uint64_t>(x));
  return out;
}

std::string format(const TypeInfo& t, const std::vector<std::uint8_t>& d) {
  char buf[64];
  if (!std::strcmp(t.name, "str")) return {d.begin(), d.end()};
  if (t.size == 0 || static_cast<std::size_t>(t.size) != d.size()) {
    std::string s;
    for (auto b : d) {
      std::snprintf(buf, sizeof buf, "%02X", b);
      s += buf;
    }
    return s;
  }
  if (t.is_signed) {
    std::int64_t v = 0;
    switch (t.size) {
      case 1: v = load_le<std::int8_t>(d); break;
      case 2: v = load_le<std::int16_t>(d); break;
      case 4: v = load_le<std::int32_t>(d); break;
      default: v = load_le<std::int64_t>(d); break;
    }
    std::snprintf(buf, sizeof buf, "%" PRId64, v);
  } else {
    const std::uint64_t v = load_le<std::uint64_t>(d);
    std::snprintf(buf, sizeof buf, "%" PRIu64 " (0x%" PRIX64 ")", v, v);
  }
  return buf;
}

std::string describe_frame(const CanFrame& f) {
  std::string s = to_string(f) + "  ";
  const unsigned fn = f.id & 0x780, node = f.id & 0x7F;
  char buf[96];
  if (f.id == 0) {
    std::snprintf(buf, sizeof buf, "NMT %s node %u", std::string(to_string(static_cast<NmtCommand>(f.data[0]))).c_str(), f.data[1]);
  } else if (f.id == cob::kSync) {
    std::snprintf(buf, sizeof buf, "SYNC");
  } else if (auto e = decode_emcy(f)) {
    return s + to_string(*e);
  } else if (f.id == cob::kTime) {
    std::snprintf(buf, sizeof buf, "TIME");
  } else if (fn == 0x700 && f.len == 1) {
    std::snprintf(buf, sizeof buf, "heartbeat node %u %s", node,
                  std::string(to_string(static_cast<NmtState>(f.data[0] & 0x7F))).c_str());
  } else if (fn == 0x580 || fn == 0x600) {
    std::snprintf(buf, sizeof buf, "SDO %s node %u %04X:%02X", fn == 0x600 ? "request" : "response", node,
                  f.data[1] | (f.data[2] << 8), f.data[3]);
  } else if (fn >= 0x180 && fn <= 0x480) {
    std::snprintf(buf, sizeof buf, "TPDO%u node %u", ((fn - 0x180) >> 8) + 1, node);
  } else if (fn >= 0x200 && fn <= 0x500) {
    std::snprintf(buf, sizeof buf, "RPDO%u node %u", ((fn - 0x200) >> 8) + 1, node);
  } else {
    buf[0] = 0;
  }
  return s + buf;
}

}  // namespace

int main(int argc, char** argv) {
  std::string ifname = "can0";
  int timeout_ms = 500;
  static const option opts[] = {{"interface", required_argument, nullptr, 'i'},
                                {"timeout", required_argument, nullptr, 't'},
                                {"help", no_argument, nullptr, 'h'},
                                {nullptr, 0, nullptr, 0}};
  for (int c; (c = getopt_long(argc, argv, "+i:t:h", opts, nullptr)) != -1;) {
    switch (c) {
      case 'i': ifname = optarg; break;
      case 't': timeout_ms = std::atoi(optarg); break;
      case 'h': usage(stdout); return 0;
      default: usage(stderr); return 2;
    }
  }
  std::vector<std::string> args(argv + optind, argv + argc);
  if (args.empty()) {
    usage(stderr);
    return 2;
  }
  const std::string cmd = args[0];
  auto need = [&](std::size_t n) {
    if (args.size() < n + 1) usage_error("'%s' needs more arguments", cmd.c_str());
  };

  int rc = 0;
  try {
    EventLoop loop;
    MasterConfig mc;
    mc.sdo_timeout = std::chrono::milliseconds(timeout_ms);
    MasterRuntime rt(loop, ifname, mc);
    Master& master = rt.master();
    auto fail = [&](const std::string& what, std::error_code ec) {
      std::fprintf(stderr, "canopenctl: %s: %s\n", what.c_str(), ec.message().c_str());
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

    if (cmd == "nmt") {
      need(2);
      static const std::pair<const char*, NmtCommand> names[] = {{"start", NmtCommand::kStart},
                                                                 {"stop", NmtCommand::kStop},
                                                                 {"preop", NmtCommand::kEnterPreOperational},
                                                                 {"reset-node", NmtCommand::kResetNode},
                                                                 {"reset-comm", NmtCommand::kResetCommunication}};
      const NmtCommand* nc = nullptr;
      for (auto& [n, c] : names)
        if (args[1] == n) nc = &c;
      if (!nc) usage_error("unknown NMT command '%s'", args[1].c_str());
      master.nmt(*nc, parse_node(args[2].c_str(), true));
      loop.post([&] { loop.stop(); });
    } else if (cmd == "read") {
      need(2);
      const auto node = parse_node(args[1].c_str());
      const auto [idx, sub] = parse_object(args[2].c_str());
      const TypeInfo& t = parse_type(args.size() > 3 ? args[3].c_str() : "hex");
      master.sdo(node).upload(idx, sub, [&, t](const SdoResult& r) {
        if (!r.ok()) return fail("read", r.error());
        std::printf("%s\n", format(t, r.data).c_str());
        loop.stop();
      });
    } else if (cmd == "write") {
      need(4);
      const auto node = parse_node(args[1].c_str());
      const auto [idx, sub] = parse_object(args[2].c_str());
      const TypeInfo& t = parse_type(args[3].c_str());
      master.sdo(node).download(idx, sub, encode(t, args[4].c_str()), [&](const SdoResult& r) {
        if (!r.ok()) return fail("write", r.error());
        loop.stop();
      });
    } else if (cmd == "pdo") {
      need(1);
      const auto node = parse_node(args[1].c_str());
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
    } else if (cmd == "status") {
      need(1);
      const auto node = parse_node(args[1].c_str());
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
      need(1);
      const auto node = parse_node(args[1].c_str());
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
    } else if (cmd == "monitor") {
      long count = args.size() > 1 ? std::atol(args[1].c_str()) : -1;
      master.set_observer([&](const CanFrame& f) {
        std::printf("%s\n", describe_frame(f).c_str());
        if (count > 0 && --count == 0) loop.stop();
      });
    } else {
      usage_error("unknown command '%s'", cmd.c_str());
    }
    loop.run();
  } catch (const std::exception& e) {
    std::fprintf(stderr, "canopenctl: %s\n", e.what());
    return 1;
  }
  return rc;
}
