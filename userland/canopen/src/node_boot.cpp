// SPDX-License-Identifier: GPL-2.0
#include "advee/canopen/node_boot.hpp"

#include <cstdio>

#include "advee/canopen/pdo.hpp"

namespace advee::canopen {

namespace {

class BootCategory : public std::error_category {
 public:
  const char* name() const noexcept override { return "canopen-boot"; }
  std::string message(int c) const override {
    switch (static_cast<BootError>(c)) {
      case BootError::kWrongDevice: return "the device is not the configured one";
    }
    return "unknown boot error";
  }
};

std::string hex32(std::uint32_t v) {
  char b[16];
  std::snprintf(b, sizeof b, "0x%08X", v);
  return b;
}

std::string where(std::uint16_t index, std::uint8_t sub) {
  char b[16];
  std::snprintf(b, sizeof b, "0x%04X:%u", index, sub);
  return b;
}

struct IdentityCheck {
  std::uint16_t index;
  std::uint8_t sub;
  const char* what;
  std::uint32_t expected;
};

bool is_pdo_object(std::uint16_t index) { return index >= 0x1400 && index <= 0x1BFF; }

}  // namespace

const std::error_category& boot_category() {
  static const BootCategory c;
  return c;
}

NodeBootConfig boot_config_from_dcf(const DeviceDescription& dcf, std::string name) {
  NodeBootConfig c;
  c.node = dcf.node_id;
  c.name = std::move(name);
  const ObjectDictionary& od = dcf.od;
  if (od.exists(0x1000, 0) && od.get<std::uint32_t>(0x1000)) c.device_type = od.get<std::uint32_t>(0x1000);
  for (std::uint8_t s = 1; s <= 3; ++s)
    if (od.exists(0x1018, s) && od.get<std::uint32_t>(0x1018, s)) c.identity[s - 1] = od.get<std::uint32_t>(0x1018, s);
  if (const OdEntry* serial = od.find(0x1018, 4); serial && serial->parameter_text)
    c.identity[3] = od.get<std::uint32_t>(0x1018, 4);

  for (PdoKind kind : {PdoKind::kRpdo, PdoKind::kTpdo}) {
    for (unsigned n = 1; n <= 512; ++n) {
      const std::uint16_t comm = pdo_comm_index(kind, n), map = pdo_map_index(kind, n);
      if (!od.exists(comm, 1) || !od.exists(map, 0)) continue;
      PdoMapping m;
      m.kind = kind;
      m.number = n;
      m.cob_id = od.get<std::uint32_t>(comm, 1);
      m.transmission_type = od.get<std::uint8_t>(comm, 2);
      for (std::uint8_t s = 1; s <= od.get<std::uint8_t>(map, 0) && s < 0x41; ++s)
        m.entries.push_back(PdoEntry::from_raw(od.get<std::uint32_t>(map, s)));
      c.pdos.push_back(std::move(m));
    }
  }

  auto configured = [](const OdEntry& e) { return e.parameter_text && e.access != Access::kReadOnly; };
  for (const auto& [key, e] : od.entries())
    if (!is_pdo_object(key.first) && configured(e)) c.configuration.push_back({key.first, key.second, e.value});
  // CiA 301 7.5.2.35-36: a device takes a new mapping only while the PDO is
  // invalid and its mapping count is 0, so the DCF's values go in that order
  // whatever order the file lists them in.
  for (std::uint16_t comm_base : {std::uint16_t{0x1400}, std::uint16_t{0x1800}}) {
    for (std::uint16_t n = 0; n < 0x200; ++n) {
      const auto comm = static_cast<std::uint16_t>(comm_base + n);
      const auto map = static_cast<std::uint16_t>(comm + 0x200);
      std::vector<std::uint8_t> comm_subs, map_subs;
      for (auto it = od.entries().lower_bound({comm, 0}); it != od.entries().end() && it->first.first == comm; ++it)
        if (configured(it->second)) comm_subs.push_back(it->first.second);
      for (auto it = od.entries().lower_bound({map, 0}); it != od.entries().end() && it->first.first == map; ++it)
        if (configured(it->second)) map_subs.push_back(it->first.second);
      if (comm_subs.empty() && map_subs.empty()) continue;
      const bool has_cob = od.exists(comm, 1);
      const auto cob = od.get<std::uint32_t>(comm, 1);
      if (has_cob) c.configuration.push_back(SdoWrite::of<std::uint32_t>(comm, 1, cob | kPdoCobInvalid));
      if (!map_subs.empty()) {
        c.configuration.push_back(SdoWrite::of<std::uint8_t>(map, 0, 0));
        for (std::uint8_t s : map_subs)
          if (s != 0) c.configuration.push_back({map, s, od.find(map, s)->value});
        c.configuration.push_back(SdoWrite::of<std::uint8_t>(map, 0, od.get<std::uint8_t>(map, 0)));
      }
      for (std::uint8_t s : comm_subs)
        if (s != 1) c.configuration.push_back({comm, s, od.find(comm, s)->value});
      if (has_cob) c.configuration.push_back(SdoWrite::of<std::uint32_t>(comm, 1, cob));
    }
  }
  return c;
}

const PdoMapping* find_pdo(const std::vector<PdoMapping>& pdos, PdoKind kind,
                           std::initializer_list<std::uint16_t> objects) {
  for (const PdoMapping& m : pdos) {
    if (m.kind != kind) continue;
    bool all = true;
    for (std::uint16_t index : objects) all = all && m.maps(index, 0);
    if (all) return &m;
  }
  return nullptr;
}

void NodeBoot::with_retry(std::function<void(SdoCallback)> op, SdoCallback done, unsigned attempt) {
  op(lifetime_.wrap([this, op, done, attempt](const SdoResult& r) {
    // Only this client's own timeout is worth repeating: an abort from the
    // device would come back the same.
    if (r.abort == SdoAbort::kTimeout && !r.aborted_by_server && attempt < cfg_.sdo_attempts) {
      ++retries_;
      return with_retry(op, done, attempt + 1);
    }
    done(r);
  }));
}

void NodeBoot::fail(std::error_code ec, const std::string& why) {
  char head[96];
  std::snprintf(head, sizeof head, "%s (node %u): boot failed: ", cfg_.name.c_str(), cfg_.node);
  reason_ = why;
  error_ = head + why;
  auto d = std::move(done_);
  done_ = nullptr;
  if (d) d(ec, error_);
}

void NodeBoot::boot(Done done) {
  lifetime_.renew();  // answers to an earlier boot are not this one's
  done_ = std::move(done);
  error_.clear();
  reason_.clear();
  mismatch_.clear();
  booted_ = false;
  check_identity(0);
}

void NodeBoot::check_identity(std::size_t i) {
  static const char* const kNames[4] = {"vendor-ID", "product code", "revision number", "serial number"};
  std::vector<IdentityCheck> checks;
  if (cfg_.device_type) checks.push_back({0x1000, 0, "device type", *cfg_.device_type});
  for (std::uint8_t s = 0; s < 4; ++s)
    if (cfg_.identity[s]) checks.push_back({0x1018, static_cast<std::uint8_t>(s + 1), kNames[s], *cfg_.identity[s]});
  if (i == checks.size()) {
    if (!mismatch_.empty()) return fail(make_error_code(BootError::kWrongDevice), "wrong device: " + mismatch_);
    // Only now is the node touched: pre-operational for the configuration.
    master_.nmt(NmtCommand::kEnterPreOperational, cfg_.node);
    return download(0);
  }
  const IdentityCheck c = checks[i];
  SdoClient& sdo = master_.sdo(cfg_.node);
  with_retry([&sdo, c](SdoCallback cb) { sdo.upload(c.index, c.sub, std::move(cb)); },
             [this, c, i](const SdoResult& r) {
               if (!r.ok())
                 return fail(r.error(), std::string("reading ") + c.what + " " + where(c.index, c.sub) + ": " +
                                            r.error().message());
               if (r.data.size() != 4)
                 return fail(make_error_code(SdoAbort::kTypeMismatch),
                             std::string("reading ") + c.what + " " + where(c.index, c.sub) + ": " +
                                 std::to_string(r.data.size()) + " bytes, expected 4");
               const auto found = load_le<std::uint32_t>(r.data);
               if (found != c.expected) {
                 if (!mismatch_.empty()) mismatch_ += "; ";
                 mismatch_ += where(c.index, c.sub) + " " + c.what + " expected " + hex32(c.expected) + ", found " +
                              hex32(found);
               }
               check_identity(i + 1);
             });
}

void NodeBoot::download(std::size_t i) {
  if (i == cfg_.configuration.size()) {
    if (cfg_.start) master_.nmt(NmtCommand::kStart, cfg_.node);
    booted_ = true;
    auto d = std::move(done_);
    done_ = nullptr;
    if (d) d({}, {});
    return;
  }
  const SdoWrite w = cfg_.configuration[i];
  SdoClient& sdo = master_.sdo(cfg_.node);
  with_retry([&sdo, w](SdoCallback cb) { sdo.download(w.index, w.sub, w.data, std::move(cb)); },
             [this, w, i](const SdoResult& r) {
               if (!r.ok()) {
                 std::uint64_t v = 0;
                 for (std::size_t b = 0; b < w.data.size() && b < 8; ++b) v |= std::uint64_t{w.data[b]} << (8 * b);
                 char val[24];
                 std::snprintf(val, sizeof val, "0x%llX", static_cast<unsigned long long>(v));
                 return fail(r.error(), "configuration " + where(w.index, w.sub) + " = " + val + " (write " +
                                            std::to_string(i + 1) + " of " +
                                            std::to_string(cfg_.configuration.size()) + "): " + r.error().message());
               }
               download(i + 1);
             });
}

}  // namespace advee::canopen
