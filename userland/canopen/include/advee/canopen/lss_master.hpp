// SPDX-License-Identifier: GPL-2.0
// CiA 305 LSS master: switch state global and selective, configure node-ID
// and bit timing, activate bit timing, store, inquire identity and node-ID,
// identify non-configured slaves, and the fastscan that finds one
// non-configured slave at a time by its LSS address. Passive like the SDO
// client: it sends through a FrameSender, learns about answers through
// handle() and about time through poll(); deadline() says when poll() is
// next needed. Services run one at a time in the order asked (FIFO queue),
// and each ends with exactly one call of its callback: answer, error code of
// the slave, or timeout. Callbacks run from handle(), poll() or
// cancel_all(), never inside the call that asked for the service; an
// LssMaster destroyed with services pending drops their callbacks uncalled.
//
// LSS answers carry no address: an answer is the answer of whichever slave
// is in configuration state (or matched the fastscan step). So after the
// first answer the master waits `settle` more for others; two or more
// answers to a confirmed service end it with kMultipleAnswers (two slaves
// were in configuration state: a node-ID configured then went to both).
#pragma once

#include <chrono>
#include <cstdint>
#include <deque>
#include <functional>
#include <memory>
#include <optional>
#include <string_view>
#include <vector>

#include "advee/canopen/clock.hpp"
#include "advee/canopen/frame.hpp"
#include "advee/canopen/lss.hpp"
#include "advee/canopen/master.hpp"
#include "advee/registration.hpp"

namespace advee::canopen {

enum class LssError : std::uint8_t {
  kNone,
  kTimeout,          // no answer within the timeout
  kRefused,          // the slave's error code is not 0 (LssResult::code, ::specific)
  kMultipleAnswers,  // more than one slave answered a confirmed service
  kNotFound,         // fastscan: no non-configured slave answered
  kLost,             // fastscan: the slave stopped answering half-way
  kInvalidArgument,  // refused before anything was sent
  kCancelled,        // cancel_all()
};
std::string_view to_string(LssError e);

struct LssResult {
  LssError error = LssError::kNone;
  std::uint8_t code = 0;      // the slave's error code (kRefused)
  std::uint8_t specific = 0;  // its implementation-specific code when code is 0xFF
  std::uint32_t value = 0;    // inquire: the word or node-ID
  unsigned answers = 0;       // answers seen (identify non-configured: how many slaves)
  bool ok() const { return error == LssError::kNone; }
};
// "refused by the slave (error code 1)", "no answer (timeout)", ...
std::string describe(const LssResult& r);

using LssCallback = std::function<void(const LssResult&)>;

struct LssFastscanResult {
  LssResult result;
  LssAddress address;  // the slave found, now in configuration state
};
using LssFastscanCallback = std::function<void(const LssFastscanResult&)>;

enum class LssInquiry : std::uint8_t { kVendor = 0, kProduct = 1, kRevision = 2, kSerial = 3, kNodeId = 4 };

struct LssMasterConfig {
  // How long a service waits for its first answer. CiA 305 leaves it to the
  // master; slaves answer within a few ms (a software slave on a loaded host
  // in tens).
  Duration timeout = std::chrono::milliseconds(100);
  // How long after the first answer others are still collected. On one CAN
  // bus the answers of several slaves follow each other within frame times;
  // the settle covers the receive path's jitter too.
  Duration settle = std::chrono::milliseconds(10);
};

class LssMaster {
 public:
  LssMaster(FrameSender send, NowFn now, LssMasterConfig cfg = {});
  // Bound to a master: receives its 0x7E4 frames and is polled with it
  // while this object lives (the master must outlive it).
  explicit LssMaster(Master& master, LssMasterConfig cfg = {});
  LssMaster(const LssMaster&) = delete;
  LssMaster& operator=(const LssMaster&) = delete;

  // Unconfirmed: done() is called once the frame is out.
  void switch_global(LssMode mode, LssCallback done);
  // The slave with this address (all four words) enters configuration state.
  void switch_selective(const LssAddress& address, LssCallback done);
  // 1..127, or kLssUnconfigured (the slave forgets its node-ID on its next
  // reset communication). Slave error code 1: out of range.
  void configure_node_id(std::uint8_t node_id, LssCallback done);
  // CiA 301 table (selector 0) index 0..9. Slave error code 1: not supported.
  void configure_bit_timing(std::uint8_t table_index, LssCallback done, std::uint8_t selector = 0);
  // Unconfirmed; every slave in configuration state switches after `delay`,
  // and again `delay` later may talk.
  void activate_bit_timing(std::chrono::milliseconds delay, LssCallback done);
  // Slave error codes: 1 storing not supported, 2 storage media access error.
  void store(LssCallback done);
  void inquire(LssInquiry what, LssCallback done);
  // Asks every slave in waiting state without node-ID to answer; waits the
  // whole timeout and reports how many did in LssResult::answers (0 is not
  // an error).
  void identify_non_configured(LssCallback done);
  // Finds one non-configured slave in waiting state and leaves it (alone) in
  // configuration state. Words that `known` gives are not scanned, only
  // confirmed (a vendor-ID, a product code). kNotFound when none answers.
  void fastscan(LssFastscanCallback done, std::array<std::optional<std::uint32_t>, 4> known = {});

  bool handle(const CanFrame& f);
  void poll();
  std::optional<TimePoint> deadline() const;

  // Ends the active and all queued services with kCancelled.
  void cancel_all();
  bool busy() const { return active_.has_value() || !queue_.empty(); }
  // Answers that came when no service waited for one (late or foreign).
  std::uint64_t unexpected_answers() const { return unexpected_; }
  const LssMasterConfig& config() const { return cfg_; }
  void set_config(const LssMasterConfig& c) { cfg_ = c; }

 private:
  // One request frame and how its answers end it.
  struct Step {
    CanFrame request;
    std::uint8_t answer_cs = 0;  // 0: unconfirmed
    bool whole_window = false;   // wait the full timeout (count answers)
    std::function<void(const std::vector<CanFrame>& answers)> done;
  };
  // A queued service: start() sends its first step, fail() ends it with an
  // error without sending anything (cancel_all()).
  struct Service {
    std::function<void()> start;
    std::function<void(LssError)> fail;
  };

  void enqueue(Service s);
  void start_next();
  void run_step(Step s);
  void finish();  // the active service has called its callback: next one
  void invalid(LssCallback done);  // ends with kInvalidArgument, sends nothing
  void confirmed(const CanFrame& request, std::uint8_t answer_cs, LssCallback done, bool check_code);

  struct Scan;
  void scan_step(const std::shared_ptr<Scan>& s);

  struct Poller final : TimedService {
    LssMaster* self = nullptr;
    void poll() override { self->poll(); }
    std::optional<TimePoint> deadline() const override { return self->deadline(); }
  };

  FrameSender send_;
  NowFn now_;
  LssMasterConfig cfg_;
  std::deque<Service> queue_;
  std::optional<Service> active_;
  std::optional<Step> step_;
  std::vector<CanFrame> answers_;
  TimePoint step_deadline_{};
  std::uint64_t unexpected_ = 0;
  Poller poller_;
  // Last, so they end first: no frame or poll reaches a half-destroyed object.
  Registration frames_;
  Registration polled_;
};

struct LssFound {
  LssAddress address;
  std::uint8_t node_id = kLssUnconfigured;  // assigned, or kLssUnconfigured
};
using LssScanCallback = std::function<void(const std::vector<LssFound>&, const LssResult&)>;

// Fastscan after fastscan until no non-configured slave answers (that end is
// success). Without `first_node_id`, every slave found stays in configuration
// state, where it takes no part in the next fastscans, until one switch
// global to waiting at the end: a scan that changes nothing. With it, each
// slave found gets the next node-ID from first_node_id on (configure
// node-ID, store if `store`, then switch global to waiting, where it boots
// with it), and the scan stops when node-ID 127 is given. Every slave is
// back in waiting state when done() is called, after an error too; the
// result is the first error (a refused store). A fastscan that lost its
// slave half-way (kLost: usually an answer that came after the settle time)
// is started again, twice at most per scan, before kLost is the result.
// The LssMaster must outlive the scan. An invalid first_node_id ends it at
// once (done() inside the call) with kInvalidArgument.
// `known` words (a vendor-ID, a product code) are passed to each fastscan:
// only slaves that have them are found, in fewer steps.
void lss_scan(LssMaster& lss, std::optional<std::uint8_t> first_node_id, bool store, LssScanCallback done,
              std::array<std::optional<std::uint32_t>, 4> known = {});

}  // namespace advee::canopen
