// SPDX-License-Identifier: GPL-2.0
#include "advee/rs485sim/bus_sim.hpp"

#include <cstdio>

#include "advee/rs485sim/devices.hpp"

namespace advee::rs485sim {

namespace {

std::string describe(const Frame& f) {
  char buf[64];
  std::snprintf(buf, sizeof(buf), "instr 0x%02x flags 0x%02x len %zu", f.instr, f.flags, f.data.size());
  return buf;
}

}  // namespace

std::unique_ptr<Device> make_device(const std::string& type, std::uint8_t addr) {
  if (type == "sd1") return std::make_unique<Sd1>(addr);
  if (type == "so1") return std::make_unique<So1>(addr);
  if (type == "sbs1") return std::make_unique<Sbs1>(addr);
  if (type == "psc1") return std::make_unique<Psc1>(addr);
  return nullptr;
}

BusSim::BusSim(std::string name, bool full_duplex, std::uint32_t seed)
    : name_(std::move(name)), full_duplex_(full_duplex), rng_(seed),
      rx_([this](const Frame& f) { on_frame(f); }) {}

Device& BusSim::add(std::unique_ptr<Device> dev) {
  if (dev->address() == kBroadcast) throw UsageError("address 0xff is the broadcast address");
  if (const auto* other = find(dev->address()))
    throw UsageError("address already taken on bus " + name_ + " by " + other->name());
  Device& d = *dev;
  d.set_rng(&rng_);
  d.set_event_sink([this, &d](const Frame& f) { on_event(d, f); });
  devices_.push_back(std::move(dev));
  return d;
}

Device* BusSim::find(std::uint8_t addr) const {
  for (const auto& d : devices_)
    if (d->address() == addr) return d.get();
  return nullptr;
}

void BusSim::feed(std::span<const std::uint16_t> words, Clock::time_point now) {
  now_ = now;
  rx_.feed(words);
}

void BusSim::on_frame(const Frame& req) {
  if (req.addr == kBroadcast) {
    if (log_) log_(name_ + ": broadcast " + describe(req));
    for (const auto& d : devices_) d->handle(req, now_);
    return;
  }
  Device* d = find(req.addr);
  if (!d) return;  // another node's frame (or a response): not ours
  const auto reply = d->handle(req, now_);
  if (!reply) {
    if (log_) log_(name_ + ": " + d->name() + " <- " + describe(req) + " -> no answer");
    return;
  }
  queue_.emplace(now_ + reply->delay, encode_words(reply->frame, reply->crc_xor));
  if (log_) {
    char buf[96];
    std::snprintf(buf, sizeof(buf), " -> flags 0x%02x len %zu in %ld us%s", reply->frame.flags,
                  reply->frame.data.size(), static_cast<long>(reply->delay.count()),
                  reply->crc_xor ? " (bad CRC)" : "");
    log_(name_ + ": " + d->name() + " <- " + describe(req) + buf);
  }
}

void BusSim::on_event(const Device& d, const Frame& f) {
  if (!full_duplex_) {
    // A half-duplex slave only talks when asked: the frame would collide.
    if (log_) log_(name_ + ": " + d.name() + " event " + describe(f) + " not sent (half-duplex bus)");
    return;
  }
  queue_.emplace(now_, encode_words(f));
  if (log_) log_(name_ + ": " + d.name() + " event " + describe(f));
}

void BusSim::poll(Clock::time_point now) {
  now_ = now;
  for (const auto& d : devices_) d->poll(now);
}

std::optional<Clock::time_point> BusSim::next_deadline() const {
  std::optional<Clock::time_point> t;
  if (!queue_.empty()) t = queue_.begin()->first;
  for (const auto& d : devices_)
    if (auto dt = d->next_deadline(); dt && (!t || *dt < *t)) t = dt;
  return t;
}

std::vector<Transmission> BusSim::take_due(Clock::time_point now) {
  std::vector<Transmission> out;
  while (!queue_.empty() && queue_.begin()->first <= now) {
    auto node = queue_.extract(queue_.begin());
    out.push_back({node.key(), std::move(node.mapped())});
  }
  return out;
}

}  // namespace advee::rs485sim
