// SPDX-License-Identifier: GPL-2.0
#include "advee/canopen/pdo_config.hpp"

#include <memory>

namespace advee::canopen {

namespace {
// Chained uploads: each reply decides what is read next.
struct ReadBack : std::enable_shared_from_this<ReadBack> {
  SdoClient* sdo = nullptr;
  PdoMapping m;
  std::uint8_t count = 0;
  std::function<void(std::error_code, const PdoMapping&)> done;

  void fail(std::error_code ec) { done(ec, m); }

  void start() {
    auto self = shared_from_this();
    const std::uint16_t comm = pdo_comm_index(m.kind, m.number);
    sdo->read<std::uint32_t>(comm, 1, [self](std::error_code ec, std::uint32_t cob) {
      if (ec) return self->fail(ec);
      self->m.cob_id = cob;
      self->read_type();
    });
  }
  void read_type() {
    auto self = shared_from_this();
    sdo->read<std::uint8_t>(pdo_comm_index(m.kind, m.number), 2, [self](std::error_code ec, std::uint8_t t) {
      if (ec) return self->fail(ec);
      self->m.transmission_type = t;
      if (self->m.kind == PdoKind::kTpdo)
        self->read_inhibit();
      else
        self->read_count();
    });
  }
  // Inhibit time and event timer are optional sub-indices (Lely GitLab #157):
  // a missing one is not an error.
  void read_inhibit() {
    auto self = shared_from_this();
    sdo->upload(pdo_comm_index(m.kind, m.number), 3, [self](const SdoResult& r) {
      if (r.ok() && r.data.size() == 2) self->m.inhibit_100us = load_le<std::uint16_t>(r.data);
      self->read_event_timer();
    });
  }
  void read_event_timer() {
    auto self = shared_from_this();
    sdo->upload(pdo_comm_index(m.kind, m.number), 5, [self](const SdoResult& r) {
      if (r.ok() && r.data.size() == 2) self->m.event_timer_ms = load_le<std::uint16_t>(r.data);
      self->read_count();
    });
  }
  void read_count() {
    auto self = shared_from_this();
    sdo->read<std::uint8_t>(pdo_map_index(m.kind, m.number), 0, [self](std::error_code ec, std::uint8_t n) {
      if (ec) return self->fail(ec);
      if (n > 64) return self->fail(make_error_code(SdoAbort::kValueTooHigh));
      self->count = n;
      self->read_entry(1);
    });
  }
  void read_entry(std::uint8_t sub) {
    if (sub > count) return done({}, m);
    auto self = shared_from_this();
    sdo->read<std::uint32_t>(pdo_map_index(m.kind, m.number), sub, [self, sub](std::error_code ec, std::uint32_t raw) {
      if (ec) return self->fail(ec);
      self->m.entries.push_back(PdoEntry::from_raw(raw));
      self->read_entry(static_cast<std::uint8_t>(sub + 1));
    });
  }
};
}  // namespace

void read_pdo_mapping(SdoClient& sdo, PdoKind kind, unsigned number,
                      std::function<void(std::error_code, const PdoMapping&)> done) {
  auto rb = std::make_shared<ReadBack>();
  rb->sdo = &sdo;
  rb->m.kind = kind;
  rb->m.number = number;
  rb->done = std::move(done);
  rb->start();
}

SdoWrite pdo_enable_write(const PdoMapping& m, bool enable) {
  const std::uint32_t cob = enable ? (m.cob_id & ~kPdoCobInvalid) : (m.cob_id | kPdoCobInvalid);
  return SdoWrite::of<std::uint32_t>(pdo_comm_index(m.kind, m.number), 1, cob);
}

std::vector<SdoWrite> pdo_remap_writes(const PdoMapping& wanted) {
  const std::uint16_t comm = pdo_comm_index(wanted.kind, wanted.number);
  const std::uint16_t map = pdo_map_index(wanted.kind, wanted.number);
  std::vector<SdoWrite> w;
  w.push_back(pdo_enable_write(wanted, false));
  w.push_back(SdoWrite::of<std::uint8_t>(map, 0, 0));
  for (std::size_t i = 0; i < wanted.entries.size(); ++i)
    w.push_back(SdoWrite::of<std::uint32_t>(map, static_cast<std::uint8_t>(i + 1), wanted.entries[i].raw()));
  w.push_back(SdoWrite::of<std::uint8_t>(map, 0, static_cast<std::uint8_t>(wanted.entries.size())));
  w.push_back(SdoWrite::of<std::uint8_t>(comm, 2, wanted.transmission_type));
  if (wanted.kind == PdoKind::kTpdo) {
    w.push_back(SdoWrite::of<std::uint16_t>(comm, 3, wanted.inhibit_100us));
    w.push_back(SdoWrite::of<std::uint16_t>(comm, 5, wanted.event_timer_ms));
  }
  if (wanted.enabled()) w.push_back(pdo_enable_write(wanted, true));
  return w;
}

}  // namespace advee::canopen
