// SPDX-License-Identifier: GPL-2.0
// advee-canopenctl dcf: `dcf download NODE FILE` configures a node from its DCF
// (or EDS, or concise DCF) the way a manager boots it (NodeBoot, CiA 302-2:
// identity checked first, then the downloads, then NMT start); `dcf concise
// NODE FILE OUT` writes the concise DCF of a DCF's configuration, with no bus.
// The file is read and checked before the CAN socket is opened
// (canopenctl_dcf.cpp, unit-tested); the run is canopenctl_dcf_run.cpp.
#pragma once

#include <functional>
#include <memory>
#include <stdexcept>
#include <string>

#include "advee/canopen/node_boot.hpp"

namespace CLI {
class App;
}

namespace advee::canopen::ctl {

// The raw strings of the command line.
struct DcfArgs {
  std::string node, file, out;
  bool no_start = false;
  unsigned attempts = 3;
};

struct DcfCommand {
  std::string name;  // "dcf download", "dcf concise"
  std::string file, out;
  bool concise_input = false;  // FILE is a concise DCF: no identity to check
  NodeBootConfig boot;         // node, identity, configuration, start, attempts
};

// A file named on the command line that cannot be read or is not a valid
// description: exit status 1, as a runtime failure (docs/command-line.md).
struct FileError : std::runtime_error {
  using std::runtime_error::runtime_error;
};

// Reads FILE: a concise DCF when its first bytes say so
// (looks_like_concise_dcf), else an EDS or DCF with $NODEID as NODE.
// Throws UsageError (bad node, a concise DCF given to `dcf concise`) or
// FileError (unreadable, invalid: every error with file:line or byte offset).
DcfCommand check_dcf(const std::string& name, const DcfArgs& a);
// "node 1 (epos): 6 objects written, identity checked (vendor ...,
// product ..., revision ...), started": what download did; retries: the
// timed-out transfers it repeated.
std::string describe_download(const DcfCommand& c, unsigned retries);

// The CLI11 part and the run (canopenctl_dcf_run.cpp).
void describe_dcf(CLI::App& app, DcfArgs& a);
// dcf concise: writes OUT; the exit status.
int write_concise(const DcfCommand& c);
// dcf download: starts the boot; end(exit status) is called once when it is
// over. The returned object must live until then.
std::unique_ptr<NodeBoot> run_dcf_download(Master& master, const DcfCommand& c, std::function<void(int)> end);

}  // namespace advee::canopen::ctl
