// SPDX-License-Identifier: GPL-2.0
#include "advee/canopen/sdo_sequence.hpp"

#include <memory>

namespace advee::canopen {

namespace {
struct Run : std::enable_shared_from_this<Run> {
  SdoClient* sdo = nullptr;
  std::vector<SdoWrite> writes;
  std::size_t next = 0;
  std::function<void(const SdoSequenceResult&)> done;

  void step() {
    if (next == writes.size()) {
      done({});
      return;
    }
    const SdoWrite& w = writes[next];
    sdo->download(w.index, w.sub, w.data, [self = shared_from_this()](const SdoResult& r) {
      if (!r.ok()) {
        self->done({r.error(), self->next, self->writes[self->next]});
        return;
      }
      ++self->next;
      self->step();
    });
  }
};
}  // namespace

void run_sdo_writes(SdoClient& sdo, std::vector<SdoWrite> writes, std::function<void(const SdoSequenceResult&)> done) {
  auto run = std::make_shared<Run>();
  run->sdo = &sdo;
  run->writes = std::move(writes);
  run->done = std::move(done);
  run->step();
}

}  // namespace advee::canopen
