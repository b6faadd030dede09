// SPDX-License-Identifier: GPL-2.0
#include "advee/canopen/lss_master.hpp"

#include <cstdio>

#include "advee/byte_order.hpp"

namespace advee::canopen {

namespace {

CanFrame lss_frame(std::uint8_t cs, std::uint32_t word = 0, std::uint8_t b5 = 0, std::uint8_t b6 = 0,
                   std::uint8_t b7 = 0) {
  CanFrame f;
  f.id = cob::kLssMaster;
  f.len = 8;  // CiA 305: every LSS frame has 8 bytes, unused ones 0
  f.data[0] = cs;
  store_le<std::uint32_t>(std::span<std::uint8_t>(f.data).subspan(1, 4), word);
  f.data[5] = b5;
  f.data[6] = b6;
  f.data[7] = b7;
  return f;
}

std::uint32_t word_of(const CanFrame& f) { return load_le<std::uint32_t>(f.payload().subspan(1, 4)); }

}  // namespace

std::string to_string(const LssAddress& a) {
  char buf[96];
  std::snprintf(buf, sizeof buf, "vendor 0x%08X product 0x%08X revision 0x%08X serial 0x%08X", a.vendor(), a.product(),
                a.revision(), a.serial());
  return buf;
}

std::optional<unsigned> lss_bit_rate_kbit(std::uint8_t table_index) {
  static constexpr unsigned kTable[] = {1000, 800, 500, 250, 125, 0, 50, 20, 10, 0};
  if (table_index > 9 || table_index == 5) return std::nullopt;
  return kTable[table_index];
}

std::string_view to_string(LssError e) {
  switch (e) {
    case LssError::kNone: return "ok";
    case LssError::kTimeout: return "no answer (timeout)";
    case LssError::kRefused: return "refused by the slave";
    case LssError::kMultipleAnswers: return "more than one slave answered";
    case LssError::kNotFound: return "no non-configured slave answered";
    case LssError::kLost: return "the slave stopped answering during the fastscan";
    case LssError::kInvalidArgument: return "invalid argument";
    case LssError::kCancelled: return "cancelled";
  }
  return "unknown LSS error";
}

std::string describe(const LssResult& r) {
  std::string s(to_string(r.error));
  if (r.error == LssError::kRefused) {
    char buf[64];
    if (r.code == 0xFF)
      std::snprintf(buf, sizeof buf, " (error code 0xFF, specific 0x%02X)", r.specific);
    else
      std::snprintf(buf, sizeof buf, " (error code %u)", r.code);
    s += buf;
  } else if (r.error == LssError::kMultipleAnswers) {
    s += " (" + std::to_string(r.answers) + " answers)";
  }
  return s;
}

LssMaster::LssMaster(FrameSender send, NowFn now, LssMasterConfig cfg)
    : send_(std::move(send)), now_(std::move(now)), cfg_(cfg) {
  poller_.self = this;
}

LssMaster::LssMaster(Master& master, LssMasterConfig cfg)
    : LssMaster([&master](const CanFrame& f) { master.send(f); }, [&master] { return master.now(); }, cfg) {
  frames_ = master.subscribe(cob::kLssSlave, [this](const CanFrame& f) { handle(f); });
  polled_ = master.attach(poller_);
}

void LssMaster::enqueue(Service s) {
  queue_.push_back(std::move(s));
  start_next();
}

void LssMaster::start_next() {
  if (active_ || queue_.empty()) return;
  active_ = std::move(queue_.front());
  queue_.pop_front();
  // A copy: start() may end the service (and so replace active_) at once.
  auto start = active_->start;
  start();
}

void LssMaster::finish() {
  active_.reset();
  start_next();
}

void LssMaster::run_step(Step s) {
  answers_.clear();
  // Unconfirmed requests end at the next poll(), never inside the call
  // that asked for them: callbacks do not run re-entrantly.
  step_deadline_ = now_() + (s.answer_cs ? cfg_.timeout : Duration{});
  const CanFrame request = s.request;
  const bool send = s.answer_cs != 0 || request.len != 0;
  step_ = std::move(s);
  if (send) send_(request);
}

bool LssMaster::handle(const CanFrame& f) {
  if (f.id != cob::kLssSlave || f.rtr) return false;
  if (!step_ || step_->answer_cs == 0 || f.len < 1 || f.data[0] != step_->answer_cs) {
    ++unexpected_;
    return true;
  }
  answers_.push_back(f);
  if (answers_.size() == 1 && !step_->whole_window) step_deadline_ = now_() + cfg_.settle;
  return true;
}

void LssMaster::poll() {
  if (!step_ || now_() < step_deadline_) return;
  // Moved out first: done() may run the next step or the next service.
  Step s = std::move(*step_);
  step_.reset();
  const std::vector<CanFrame> answers = std::move(answers_);
  answers_.clear();
  s.done(answers);
}

std::optional<TimePoint> LssMaster::deadline() const {
  if (!step_) return std::nullopt;
  return step_deadline_;
}

void LssMaster::cancel_all() {
  step_.reset();
  answers_.clear();
  std::optional<Service> active = std::move(active_);
  active_.reset();
  std::deque<Service> queued = std::move(queue_);
  queue_.clear();
  if (active) active->fail(LssError::kCancelled);
  for (auto& s : queued) s.fail(LssError::kCancelled);
}

namespace {
auto failing(LssCallback done) {
  return [done](LssError e) {
    LssResult r;
    r.error = e;
    if (done) done(r);
  };
}
}  // namespace

void LssMaster::confirmed(const CanFrame& request, std::uint8_t answer_cs, LssCallback done, bool check_code) {
  Step s;
  s.request = request;
  s.answer_cs = answer_cs;
  s.done = [this, done = std::move(done), check_code, answer_cs](const std::vector<CanFrame>& a) {
    LssResult r;
    r.answers = static_cast<unsigned>(a.size());
    if (a.empty()) {
      r.error = LssError::kTimeout;
    } else {
      const CanFrame& f = a.front();
      r.value = answer_cs == lss_cs::kInquireNodeId ? f.data[1] : word_of(f);
      if (check_code) {
        r.code = f.data[1];
        r.specific = f.data[2];
      }
      if (a.size() > 1)
        r.error = LssError::kMultipleAnswers;
      else if (r.code != 0)
        r.error = LssError::kRefused;
    }
    finish();
    if (done) done(r);
  };
  run_step(std::move(s));
}

void LssMaster::switch_global(LssMode mode, LssCallback done) {
  enqueue({[this, mode, done] {
             Step s;
             s.request = lss_frame(lss_cs::kSwitchGlobal, static_cast<std::uint8_t>(mode));
             s.done = [this, done](const std::vector<CanFrame>&) {
               finish();
               if (done) done({});
             };
             run_step(std::move(s));
           },
           failing(done)});
}

void LssMaster::switch_selective(const LssAddress& address, LssCallback done) {
  enqueue({[this, address, done] {
             // Vendor, product and revision are only latched by the slaves;
             // the serial number's frame makes the matching slave answer.
             for (std::uint8_t i = 0; i < 3; ++i)
               send_(lss_frame(static_cast<std::uint8_t>(lss_cs::kSwitchSelectiveVendor + i), address.words[i]));
             confirmed(lss_frame(lss_cs::kSwitchSelectiveVendor + 3, address.words[3]), lss_cs::kSwitchSelectiveAnswer,
                       done, false);
           },
           failing(done)});
}

void LssMaster::configure_node_id(std::uint8_t node_id, LssCallback done) {
  if (!is_valid_node_id(node_id) && node_id != kLssUnconfigured) return invalid(std::move(done));
  enqueue({[this, node_id, done] {
             confirmed(lss_frame(lss_cs::kConfigureNodeId, node_id), lss_cs::kConfigureNodeId, done, true);
           },
           failing(done)});
}

void LssMaster::configure_bit_timing(std::uint8_t table_index, LssCallback done, std::uint8_t selector) {
  enqueue({[this, table_index, selector, done] {
             confirmed(lss_frame(lss_cs::kConfigureBitTiming, static_cast<std::uint32_t>(selector) | (table_index << 8)),
                       lss_cs::kConfigureBitTiming, done, true);
           },
           failing(done)});
}

void LssMaster::activate_bit_timing(std::chrono::milliseconds delay, LssCallback done) {
  if (delay.count() < 0 || delay.count() > 0xFFFF) return invalid(std::move(done));
  enqueue({[this, delay, done] {
             Step s;
             s.request = lss_frame(lss_cs::kActivateBitTiming, static_cast<std::uint32_t>(delay.count()));
             s.done = [this, done](const std::vector<CanFrame>&) {
               finish();
               if (done) done({});
             };
             run_step(std::move(s));
           },
           failing(done)});
}

void LssMaster::store(LssCallback done) {
  enqueue({[this, done] { confirmed(lss_frame(lss_cs::kStore), lss_cs::kStore, done, true); }, failing(done)});
}

void LssMaster::inquire(LssInquiry what, LssCallback done) {
  const auto cs = static_cast<std::uint8_t>(lss_cs::kInquireVendor + static_cast<std::uint8_t>(what));
  enqueue({[this, cs, done] { confirmed(lss_frame(cs), cs, done, false); }, failing(done)});
}

void LssMaster::identify_non_configured(LssCallback done) {
  enqueue({[this, done] {
             Step s;
             s.request = lss_frame(lss_cs::kIdentifyNonConfigured);
             s.answer_cs = lss_cs::kIdentifyNonConfiguredAnswer;
             s.whole_window = true;
             s.done = [this, done](const std::vector<CanFrame>& a) {
               LssResult r;
               r.answers = static_cast<unsigned>(a.size());
               finish();
               if (done) done(r);
             };
             run_step(std::move(s));
           },
           failing(done)});
}

void LssMaster::invalid(LssCallback done) {
  // Through the queue like any service, so the callback never runs inside
  // the call that asked for it.
  enqueue({[this, done] {
             Step s;  // sends nothing (len 0, unconfirmed)
             s.done = [this, done](const std::vector<CanFrame>&) {
               finish();
               LssResult r;
               r.error = LssError::kInvalidArgument;
               if (done) done(r);
             };
             run_step(std::move(s));
           },
           failing(done)});
}

// Fastscan (CiA 305): a reset step makes every non-configured slave in
// waiting state answer and restart its scan at the vendor-ID. Then, word by
// word, bit by bit from bit 31: the master sends its guess with bit n = 0
// and asks "whose bits 31..n equal these?"; an answer keeps the 0, silence
// means every remaining slave has a 1 there. Each word is confirmed with all
// 32 bits (bit-checked 0), which moves the matching slaves on to the next
// word; the confirm of the serial number (next = vendor-ID) puts the one
// slave left into configuration state. Slaves that lost on a bit wait for
// the next reset.
struct LssMaster::Scan {
  LssFastscanCallback done;
  std::array<std::optional<std::uint32_t>, 4> known;
  LssAddress address;
  enum class Phase { kReset, kBit, kConfirm } phase = Phase::kReset;
  std::uint8_t sub = 0;
  std::uint8_t bit = 31;
};

void LssMaster::fastscan(LssFastscanCallback done, std::array<std::optional<std::uint32_t>, 4> known) {
  auto fail = [done](LssError e) {
    LssFastscanResult r;
    r.result.error = e;
    if (done) done(r);
  };
  enqueue({[this, done, known] {
             auto s = std::make_shared<Scan>();
             s->done = done;
             s->known = known;
             scan_step(s);
           },
           fail});
}

void LssMaster::scan_step(const std::shared_ptr<Scan>& s) {
  using Phase = Scan::Phase;
  Step step;
  step.answer_cs = lss_cs::kIdentifySlave;
  const std::uint8_t next = static_cast<std::uint8_t>((s->sub + 1) % 4);
  switch (s->phase) {
    case Phase::kReset: step.request = lss_frame(lss_cs::kFastscan, 0, kFastscanReset); break;
    case Phase::kBit:
      step.request = lss_frame(lss_cs::kFastscan, s->address.words[s->sub], s->bit, s->sub, s->sub);
      break;
    case Phase::kConfirm:
      step.request = lss_frame(lss_cs::kFastscan, s->address.words[s->sub], 0, s->sub, next);
      break;
  }
  step.done = [this, s](const std::vector<CanFrame>& a) {
    const bool answered = !a.empty();
    auto end = [this, s](LssError e) {
      LssFastscanResult r;
      r.result.error = e;
      r.address = s->address;
      finish();
      if (s->done) s->done(r);
    };
    // The next word: scanned bit by bit, or only confirmed when known.
    auto begin_word = [s] {
      if (s->known[s->sub]) {
        s->address.words[s->sub] = *s->known[s->sub];
        s->phase = Scan::Phase::kConfirm;
      } else {
        s->address.words[s->sub] = 0;
        s->phase = Scan::Phase::kBit;
        s->bit = 31;
      }
    };
    switch (s->phase) {
      case Scan::Phase::kReset:
        if (!answered) return end(LssError::kNotFound);
        begin_word();
        break;
      case Scan::Phase::kBit:
        if (!answered) s->address.words[s->sub] |= 1u << s->bit;
        if (s->bit == 0)
          s->phase = Scan::Phase::kConfirm;
        else
          --s->bit;
        break;
      case Scan::Phase::kConfirm:
        // A known word no slave has: none to find. A scanned word that no
        // slave confirms: the slave left (reset, unplugged) half-way.
        if (!answered) return end(s->known[s->sub] ? LssError::kNotFound : LssError::kLost);
        if (s->sub == 3) return end(LssError::kNone);
        ++s->sub;
        begin_word();
        break;
    }
    scan_step(s);
  };
  run_step(std::move(step));
}

}  // namespace advee::canopen

namespace advee::canopen {

namespace {
// At most this many slaves per scan: a faulty slave that answers every
// fastscan step must not keep the scan going for ever.
constexpr std::size_t kMaxScanned = 127;
// Fastscans that lost their slave are started again this often per scan:
// an answer that came after the settle time counts for the next step and
// sets a wrong bit, which the word's confirm then finds (on vcan, where the
// answers of several slaves are separate frames, under load).
constexpr int kFastscanRetries = 2;

struct ScanState {
  LssMaster* lss = nullptr;
  std::optional<std::uint8_t> next_id;
  bool store = false;
  std::vector<LssFound> found;
  LssScanCallback done;
  std::array<std::optional<std::uint32_t>, 4> known;
  int retries = kFastscanRetries;
};

void scan_end(const std::shared_ptr<ScanState>& st, LssResult r) {
  st->lss->switch_global(LssMode::kWaiting, [st, r](const LssResult&) { st->done(st->found, r); });
}

void scan_next(const std::shared_ptr<ScanState>& st) {
  if (st->found.size() >= kMaxScanned || (st->next_id && *st->next_id > 127)) return scan_end(st, {});
  st->lss->fastscan([st](const LssFastscanResult& fr) {
    if (fr.result.error == LssError::kNotFound) return scan_end(st, {});
    if (fr.result.error == LssError::kLost && st->retries > 0) {
      --st->retries;
      // While numbering, a slave that did reach configuration state (its
      // last answer missed) goes back to waiting so that it cannot share
      // the next node-ID; while listing, the slaves found stay put.
      if (!st->next_id) return scan_next(st);
      return st->lss->switch_global(LssMode::kWaiting, [st](const LssResult&) { scan_next(st); });
    }
    if (!fr.result.ok()) return scan_end(st, fr.result);
    st->found.push_back({fr.address, kLssUnconfigured});
    if (!st->next_id) return scan_next(st);
    const std::uint8_t id = *st->next_id;
    st->lss->configure_node_id(id, [st, id](const LssResult& r) {
      if (!r.ok()) return scan_end(st, r);
      st->found.back().node_id = id;
      st->next_id = static_cast<std::uint8_t>(id + 1);
      auto to_waiting = [st] {
        // Only the slave just found is in configuration state: it leaves
        // it and boots with its node-ID, so the next fastscan skips it.
        st->lss->switch_global(LssMode::kWaiting, [st](const LssResult&) { scan_next(st); });
      };
      if (!st->store) return to_waiting();
      st->lss->store([st, to_waiting](const LssResult& sr) {
        if (!sr.ok()) return scan_end(st, sr);
        to_waiting();
      });
    });
  }, st->known);
}
}  // namespace

void lss_scan(LssMaster& lss, std::optional<std::uint8_t> first_node_id, bool store, LssScanCallback done,
              std::array<std::optional<std::uint32_t>, 4> known) {
  auto st = std::make_shared<ScanState>();
  st->lss = &lss;
  st->next_id = first_node_id;
  st->store = store;
  st->done = std::move(done);
  st->known = known;
  if (first_node_id && !is_valid_node_id(*first_node_id)) {
    LssResult r;
    r.error = LssError::kInvalidArgument;
    return st->done({}, r);
  }
  scan_next(st);
}

}  // namespace advee::canopen
