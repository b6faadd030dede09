// SPDX-License-Identifier: GPL-2.0
// A DriveSource fed by text lines "SPEED_MPS STEERING_DEG" on a file
// descriptor (a pipe, a FIFO, stdin): the hook through which whatever reads
// the simulated EPOS/IclA (or a person, or a test) drives the virtual robot
// until advee-canopen-sim-drive exposes its state. The last complete line holds;
// until the first one the robot stands still.
#pragma once

#include <string>

#include "advee/robotsim/sinks.hpp"
#include "advee/unique_fd.hpp"

namespace advee::robotsim {

class StreamDrive : public DriveSource {
 public:
  // Takes ownership of `fd` and makes it non-blocking.
  explicit StreamDrive(UniqueFd fd);
  // Reads what arrived (never blocks) and returns the latest command. A bad
  // line throws ConfigError naming it; end of input keeps the last command.
  DriveCommand command(double time_s) override;
  bool at_eof() const { return eof_; }

 private:
  UniqueFd fd_;
  std::string pending_;
  DriveCommand last_;
  bool eof_ = false;
};

// Parses one "SPEED_MPS STEERING_DEG" line.
DriveCommand parse_drive_line(const std::string& line);

}  // namespace advee::robotsim
