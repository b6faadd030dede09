// SPDX-License-Identifier: GPL-2.0
#include "advee/rs485sim/control.hpp"

#include <algorithm>
#include <cstdio>
#include <sstream>

#include "advee/rs485sim/devices.hpp"

namespace advee::rs485sim {

namespace {

std::vector<std::string> split(const std::string& line) {
  std::istringstream in(line);
  std::vector<std::string> t;
  for (std::string w; in >> w;) t.push_back(w);
  return t;
}

}  // namespace

FaultSpec parse_fault_spec(const std::string& s) {
  FaultSpec f;
  if (s == "once") {
    f.once = 1;
  } else if (s.rfind("once:", 0) == 0) {
    f.once = static_cast<unsigned>(parse_int(s.substr(5), "once count", 0, 1000000));
  } else {
    f.probability = parse_double(s, "fault probability");
    if (f.probability < 0.0 || f.probability > 1.0)
      throw UsageError("fault probability: " + s + " not in 0..1");
  }
  return f;
}

FaultSpec& fault_by_name(Faults& f, const std::string& kind) {
  if (kind == "no-answer") return f.no_answer;
  if (kind == "bad-crc") return f.bad_crc;
  if (kind == "unkinstr") return f.unkinstr;
  if (kind == "slow") return f.slow;
  throw UsageError("fault kind '" + kind + "': one of no-answer, bad-crc, unkinstr, slow");
}

const char* Control::help() {
  return "list\n"
         "show DEV\n"
         "stats DEV | reset-stats DEV\n"
         "set DEV firmware MAJOR MINOR\n"
         "set sd1@A srf INDEX|all METRES|none | ir INDEX|all METRES|none | pause MASK\n"
         "set so1@A ticks LEFT RIGHT | rate LEFT_PER_S RIGHT_PER_S\n"
         "set sbs1@A beacon ID DEGREES QUALITY | beacon ID none | ids ID...\n"
         "set psc1@A status MASK | current CH|all AMPS|none | pause ENGAGED SOURCES |"
         " pause-period MS | power-period MS\n"
         "event psc1@A pause ENGAGED SOURCES | power\n"
         "fault DEV no-answer|bad-crc|unkinstr|slow once|once:N|PROBABILITY\n"
         "fault DEV slow-ms MS | fault DEV clear\n"
         "log on|off\n"
         "DEV = [BUS:]TYPE@ADDRESS, e.g. sd1@0x10 or a:sd1@0x10\n";
}

std::pair<BusSim*, Device*> Control::device(const std::string& spec) const {
  std::string bus, rest = spec;
  if (const auto colon = spec.find(':'); colon != std::string::npos) {
    bus = spec.substr(0, colon);
    rest = spec.substr(colon + 1);
  }
  const auto at = rest.find('@');
  if (at == std::string::npos) throw UsageError("device '" + spec + "': want [BUS:]TYPE@ADDRESS");
  const std::string type = rest.substr(0, at);
  const auto addr = static_cast<std::uint8_t>(parse_int(rest.substr(at + 1), "address", 0, 0xfe));
  std::pair<BusSim*, Device*> found{nullptr, nullptr};
  for (auto* b : buses_) {
    if (!bus.empty() && b->name() != bus) continue;
    Device* d = b->find(addr);
    if (!d || d->type() != type) continue;
    if (found.second) throw UsageError("device '" + spec + "' is on several buses: name the bus (BUS:" + rest + ")");
    found = {b, d};
  }
  if (!found.second) throw UsageError("no device " + spec);
  return found;
}

std::string Control::stats(const Device& d) const {
  const auto& s = d.stats();
  std::ostringstream o;
  o << "requests=" << s.requests << " executed=" << s.executed << " resends=" << s.resends
    << " broadcasts=" << s.broadcasts << " unkinstr=" << s.unkinstr << " dropped=" << s.dropped
    << " corrupted=" << s.corrupted << " slow=" << s.slow << " events=" << s.events;
  for (const auto& [instr, n] : s.per_instr) {
    char buf[32];
    std::snprintf(buf, sizeof(buf), " exec[0x%02x]=%llu", instr, static_cast<unsigned long long>(n));
    o << buf;
  }
  return o.str();
}

std::string Control::execute(const std::string& line, Clock::time_point now) try {
  const auto t = split(line);
  if (t.empty()) throw UsageError("empty command (try 'help')");
  const std::string& cmd = t[0];
  if (cmd == "help") return std::string("ok\n") + help();
  if (cmd == "list") {
    std::string out = "ok";
    for (auto* b : buses_)
      for (const auto& d : b->devices()) out += "\n" + b->name() + ":" + d->name();
    return out;
  }
  if (cmd == "log" && t.size() == 2 && (t[1] == "on" || t[1] == "off")) {
    logging_ = t[1] == "on";
    return "ok";
  }
  static const std::vector<std::string> kWithDevice{"show", "stats", "reset-stats", "set", "event", "fault"};
  if (std::find(kWithDevice.begin(), kWithDevice.end(), cmd) == kWithDevice.end())
    throw UsageError("unknown command '" + line + "' (try 'help')");
  if (t.size() < 2) throw UsageError("'" + cmd + "' needs a device (try 'help')");
  auto [bus, dev] = device(t[1]);
  const std::vector<std::string> args(t.begin() + std::min<std::size_t>(3, t.size()), t.end());
  if (cmd == "show" && t.size() == 2) return "ok " + dev->show(now);
  if (cmd == "stats" && t.size() == 2) return "ok " + stats(*dev);
  if (cmd == "reset-stats" && t.size() == 2) {
    dev->reset_stats();
    return "ok";
  }
  if (cmd == "set" && t.size() >= 3) {
    if (t[2] == "firmware" && args.size() == 2) {
      dev->set_firmware(static_cast<std::uint8_t>(parse_int(args[0], "major", 0, 255)),
                        static_cast<std::uint8_t>(parse_int(args[1], "minor", 0, 255)));
    } else {
      dev->set(t[2], args);
    }
    return "ok";
  }
  if (cmd == "event" && t.size() >= 3) {
    auto* psc = dynamic_cast<Psc1*>(dev);
    if (!psc) throw UsageError("only psc1 sends events");
    if (!bus->full_duplex()) throw UsageError("bus " + bus->name() + " is half-duplex: no events");
    if (t[2] == "pause" && args.size() == 2) {
      psc->send_pause_event(parse_int(args[0], "engaged", 0, 1) != 0,
                            static_cast<std::uint8_t>(parse_int(args[1], "sources", 0, 0xff)));
    } else if (t[2] == "power" && args.empty()) {
      psc->send_power_event();
    } else {
      throw UsageError("event psc1@A pause ENGAGED SOURCES | power");
    }
    return "ok";
  }
  if (cmd == "fault" && t.size() >= 3) {
    if (t[2] == "clear" && args.empty()) {
      const auto delay = dev->faults().slow_delay;
      dev->faults() = Faults{};
      dev->faults().slow_delay = delay;
    } else if (t[2] == "slow-ms" && args.size() == 1) {
      dev->faults().slow_delay = std::chrono::milliseconds(parse_int(args[0], "slow-ms", 0, 60000));
    } else if (args.size() == 1) {
      fault_by_name(dev->faults(), t[2]) = parse_fault_spec(args[0]);
    } else {
      throw UsageError("fault DEV KIND once|once:N|PROBABILITY, fault DEV slow-ms MS, fault DEV clear");
    }
    return "ok";
  }
  throw UsageError("unknown command '" + line + "' (try 'help')");
} catch (const UsageError& e) {
  return std::string("error: ") + e.what();
}

}  // namespace advee::rs485sim
