// SPDX-License-Identifier: GPL-2.0
#include "advee/rs485sim/config.hpp"

#include <yaml-cpp/yaml.h>

#include <algorithm>
#include <climits>
#include <fstream>
#include <set>
#include <sstream>

#include "advee/rs485sim/control.hpp"
#include "advee/rs485sim/devices.hpp"

namespace advee::rs485sim {

namespace {

class Loader {
 public:
  Loader(std::string name, std::optional<std::uint32_t> seed) : name_(std::move(name)), seed_(seed) {}

  [[noreturn]] void fail(const YAML::Node& n, const std::string& field, const std::string& msg) const {
    throw_config_error(name_, n.Mark().line, field, msg);
  }

  // Every key of a map must be known: a typo is an error, not a silent default.
  void check_keys(const YAML::Node& map, const std::string& where, std::set<std::string> known) const {
    if (!map.IsMap()) fail(map, where, "must be a mapping");
    for (const auto& kv : map) {
      const auto key = kv.first.as<std::string>();
      if (!known.count(key)) {
        std::string list;
        for (const auto& k : known) list += (list.empty() ? "" : ", ") + k;
        fail(kv.first, where + "." + key, "unknown key (known: " + list + ")");
      }
    }
  }

  template <typename F>
  auto value(const YAML::Node& n, const std::string& field, F&& parse) const {
    if (!n.IsScalar()) fail(n, field, "must be a single value");
    try {
      return parse(n.Scalar());
    } catch (const UsageError& e) {
      fail(n, field, e.what());
    }
  }
  long long integer(const YAML::Node& n, const std::string& field, long long min, long long max) const {
    return value(n, field, [&](const std::string& s) { return parse_int(s, field.c_str(), min, max); });
  }
  double number(const YAML::Node& n, const std::string& field) const {
    return value(n, field, [&](const std::string& s) { return parse_double(s, field.c_str()); });
  }
  // A number, or null / "none" for "no reading".
  std::optional<double> reading(const YAML::Node& n, const std::string& field) const {
    if (n.IsNull() || (n.IsScalar() && n.Scalar() == "none")) return std::nullopt;
    const double v = number(n, field);
    if (v < 0) fail(n, field, "negative");
    return v;
  }
  const YAML::Node& sequence(const YAML::Node& n, const std::string& field, std::size_t max) const {
    if (!n.IsSequence()) fail(n, field, "must be a list");
    if (n.size() > max) fail(n, field, "at most " + std::to_string(max) + " values");
    return n;
  }

  SimConfig load(const YAML::Node& root) const {
    SimConfig cfg;
    if (!root.IsMap()) fail(root, "top level", "must be a mapping with 'buses'");
    check_keys(root, "top level", {"control", "seed", "buses"});
    if (root["control"]) cfg.control = value(root["control"], "control", [](const std::string& s) { return s; });
    if (root["seed"]) cfg.seed = static_cast<std::uint32_t>(integer(root["seed"], "seed", 0, 0xffffffffLL));
    if (seed_) cfg.seed = *seed_;
    const auto buses = root["buses"];
    if (!buses) fail(root, "buses", "missing (a list of buses)");
    if (!buses.IsSequence() || buses.size() == 0) fail(buses, "buses", "must be a non-empty list");
    std::set<std::string> names, wires;
    for (std::size_t i = 0; i < buses.size(); ++i) {
      const auto b = buses[i];
      const std::string where = "buses[" + std::to_string(i) + "]";
      check_keys(b, where, {"name", "wire", "duplex", "devices"});
      for (const char* k : {"name", "wire", "devices"})
        if (!b[k]) fail(b, where + "." + k, "missing");
      const auto name = value(b["name"], where + ".name", [](const std::string& s) { return s; });
      const auto wire = value(b["wire"], where + ".wire", [](const std::string& s) { return s; });
      if (!names.insert(name).second) fail(b["name"], where + ".name", "bus '" + name + "' defined twice");
      if (!wires.insert(wire).second) fail(b["wire"], where + ".wire", wire + " used by two buses");
      bool full = false;
      if (b["duplex"]) {
        const auto d = value(b["duplex"], where + ".duplex", [](const std::string& s) { return s; });
        if (d != "half" && d != "full") fail(b["duplex"], where + ".duplex", "half or full, not '" + d + "'");
        full = d == "full";
      }
      auto bus = std::make_unique<BusSim>(name, full, cfg.seed + static_cast<std::uint32_t>(i));
      const auto devs = b["devices"];
      if (!devs.IsSequence()) fail(devs, where + ".devices", "must be a list");
      for (std::size_t j = 0; j < devs.size(); ++j)
        add_device(*bus, devs[j], where + ".devices[" + std::to_string(j) + "]");
      cfg.buses.push_back({std::move(bus), wire});
    }
    return cfg;
  }

 private:
  void add_device(BusSim& bus, const YAML::Node& n, const std::string& where) const {
    if (!n.IsMap()) fail(n, where, "must be a mapping");
    if (!n["type"]) fail(n, where + ".type", "missing (sd1, so1, sbs1 or psc1)");
    if (!n["address"]) fail(n, where + ".address", "missing");
    const auto type = value(n["type"], where + ".type", [](const std::string& s) { return s; });
    const auto addr = static_cast<std::uint8_t>(integer(n["address"], where + ".address", 0, 0xfe));
    std::set<std::string> keys{"type", "address", "firmware", "response_us", "faults"};
    if (type == "sd1") keys.insert({"srf_m", "ir_m", "pause_sources"});
    else if (type == "so1") keys.insert({"ticks", "rate"});
    else if (type == "sbs1") keys.insert({"ids", "beacons"});
    else if (type == "psc1") keys.insert({"status", "currents_a", "pause_period_ms", "power_period_ms"});
    else fail(n["type"], where + ".type", "unknown device type '" + type + "' (sd1, so1, sbs1, psc1)");
    check_keys(n, where, keys);

    auto dev = make_device(type, addr);
    const auto now = Clock::now();
    if (const auto fw = n["firmware"]) {
      sequence(fw, where + ".firmware", 2);
      if (fw.size() != 2) fail(fw, where + ".firmware", "want [MAJOR, MINOR]");
      dev->set_firmware(static_cast<std::uint8_t>(integer(fw[0], where + ".firmware", 0, 255)),
                        static_cast<std::uint8_t>(integer(fw[1], where + ".firmware", 0, 255)));
    }
    if (const auto rt = n["response_us"]) {
      long lo, hi;
      if (rt.IsSequence()) {
        if (rt.size() != 2) fail(rt, where + ".response_us", "want MICROSECONDS or [MIN, MAX]");
        lo = integer(rt[0], where + ".response_us", 0, 10000000);
        hi = integer(rt[1], where + ".response_us", lo, 10000000);
      } else {
        lo = hi = integer(rt, where + ".response_us", 0, 10000000);
      }
      dev->set_response_time(std::chrono::microseconds(lo), std::chrono::microseconds(hi));
    }
    if (const auto f = n["faults"]) load_faults(*dev, f, where + ".faults");

    if (auto* sd1 = dynamic_cast<Sd1*>(dev.get())) {
      if (const auto s = n["srf_m"])
        for (std::size_t i = 0; i < sequence(s, where + ".srf_m", Sd1::kSrf).size(); ++i)
          sd1->set_srf(i, reading(s[i], where + ".srf_m"));
      if (const auto s = n["ir_m"])
        for (std::size_t i = 0; i < sequence(s, where + ".ir_m", Sd1::kIr).size(); ++i)
          sd1->set_ir(i, reading(s[i], where + ".ir_m"));
      if (const auto p = n["pause_sources"])
        sd1->raise_pause(static_cast<std::uint8_t>(integer(p, where + ".pause_sources", 0, 255)));
    } else if (auto* so1 = dynamic_cast<So1*>(dev.get())) {
      if (const auto t = n["ticks"]) {
        if (sequence(t, where + ".ticks", 2).size() != 2) fail(t, where + ".ticks", "want [LEFT, RIGHT]");
        so1->set_ticks(integer(t[0], where + ".ticks", LONG_MIN, LONG_MAX),
                       integer(t[1], where + ".ticks", LONG_MIN, LONG_MAX), now);
      }
      if (const auto r = n["rate"]) {
        if (sequence(r, where + ".rate", 2).size() != 2) fail(r, where + ".rate", "want [LEFT, RIGHT] ticks/s");
        so1->set_rate(number(r[0], where + ".rate"), number(r[1], where + ".rate"), now);
      }
    } else if (auto* sbs1 = dynamic_cast<Sbs1*>(dev.get())) {
      if (const auto ids = n["ids"]) {
        std::vector<std::uint8_t> v;
        for (const auto& id : sequence(ids, where + ".ids", 255))
          v.push_back(static_cast<std::uint8_t>(integer(id, where + ".ids", 0, 255)));
        sbs1->set_initial_ids(std::move(v));
      }
      if (const auto bs = n["beacons"]) {
        sequence(bs, where + ".beacons", 256);
        for (std::size_t k = 0; k < bs.size(); ++k) {
          const auto b = bs[k];
          const std::string w = where + ".beacons[" + std::to_string(k) + "]";
          check_keys(b, w, {"id", "bearing_deg", "quality"});
          for (const char* key : {"id", "bearing_deg"})
            if (!b[key]) fail(b, w + "." + key, "missing");
          const auto id = static_cast<std::uint8_t>(integer(b["id"], w + ".id", 0, 255));
          const double deg = number(b["bearing_deg"], w + ".bearing_deg");
          const auto q = b["quality"] ? integer(b["quality"], w + ".quality", 0, 255) : 255;
          sbs1->set_beacon(id, Sbs1::Sighting{deg, static_cast<std::uint8_t>(q)});
        }
      }
    } else if (auto* psc1 = dynamic_cast<Psc1*>(dev.get())) {
      if (const auto s = n["status"])
        psc1->set_boot_status(static_cast<std::uint8_t>(integer(s, where + ".status", 0, 255)));
      if (const auto c = n["currents_a"])
        for (std::size_t i = 0; i < sequence(c, where + ".currents_a", Psc1::kChannels).size(); ++i)
          psc1->set_current(i, reading(c[i], where + ".currents_a"));
      if (const auto p = n["pause_period_ms"])
        psc1->set_pause_period(std::chrono::milliseconds(integer(p, where + ".pause_period_ms", 0, 3600000)), now);
      if (const auto p = n["power_period_ms"])
        psc1->set_power_period(std::chrono::milliseconds(integer(p, where + ".power_period_ms", 0, 3600000)), now);
      if ((n["pause_period_ms"] || n["power_period_ms"]) && !bus.full_duplex())
        fail(n, where, "periodic events need a full-duplex bus (duplex: full)");
    }
    try {
      bus.add(std::move(dev));
    } catch (const UsageError& e) {
      fail(n["address"], where + ".address", e.what());
    }
  }

  void load_faults(Device& dev, const YAML::Node& f, const std::string& where) const {
    check_keys(f, where, {"no_answer", "bad_crc", "unkinstr", "slow", "slow_ms"});
    for (const auto& kv : f) {
      const auto key = kv.first.as<std::string>();
      if (key == "slow_ms") {
        dev.faults().slow_delay = std::chrono::milliseconds(integer(kv.second, where + ".slow_ms", 0, 60000));
        continue;
      }
      std::string kind = key;
      std::replace(kind.begin(), kind.end(), '_', '-');
      fault_by_name(dev.faults(), kind) =
          value(kv.second, where + "." + key, [](const std::string& s) { return parse_fault_spec(s); });
    }
  }

  std::string name_;
  std::optional<std::uint32_t> seed_;
};

}  // namespace

SimConfig load_config_string(const std::string& yaml, const std::string& name,
                             std::optional<std::uint32_t> seed) {
  YAML::Node root;
  try {
    root = YAML::Load(yaml);
  } catch (const YAML::ParserException& e) {
    throw_config_error(name, e.mark.line, "", "YAML syntax: " + e.msg);
  }
  return Loader(name, seed).load(root);
}

SimConfig load_config_file(const std::string& path, std::optional<std::uint32_t> seed) {
  std::ifstream in(path);
  if (!in) throw ConfigError(path + ": cannot open");
  std::ostringstream text;
  text << in.rdbuf();
  return load_config_string(text.str(), path, seed);
}

}  // namespace advee::rs485sim
