// SPDX-License-Identifier: GPL-2.0
// The control commands (one line each, e.g. "set sd1@0x10 srf 3 1.25"): how
// a world model or a test changes readings, raises events and injects
// faults while the simulator runs. docs/rs485-sim.md lists them.
#pragma once

#include <string>
#include <vector>

#include "advee/rs485sim/bus_sim.hpp"

namespace advee::rs485sim {

class Control {
 public:
  explicit Control(std::vector<BusSim*> buses) : buses_(std::move(buses)) {}

  // Executes one command line; the reply starts with "ok" or "error:".
  std::string execute(const std::string& line, Clock::time_point now);
  // The reply to "help".
  static const char* help();

  bool logging() const { return logging_; }
  void set_logging(bool on) { logging_ = on; }

 private:
  // "[BUS:]TYPE@ADDR": throws UsageError when none or several devices match.
  std::pair<BusSim*, Device*> device(const std::string& spec) const;
  std::string stats(const Device& d) const;

  std::vector<BusSim*> buses_;
  bool logging_ = false;
};

// "once", "once:N" or a probability 0..1, for the control command and the config.
FaultSpec parse_fault_spec(const std::string& s);
// The FaultSpec member of Faults named by a fault kind (no-answer, bad-crc, unkinstr, slow).
FaultSpec& fault_by_name(Faults& f, const std::string& kind);

}  // namespace advee::rs485sim
