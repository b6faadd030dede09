// SPDX-License-Identifier: GPL-2.0
// advee-canopenctl dcf: the CLI11 description and the runs.
#include <CLI/CLI.hpp>

#include <cerrno>
#include <cstdio>
#include <cstring>
#include <fstream>

#include "advee/canopen/concise_dcf.hpp"
#include "advee/cli.hpp"
#include "canopenctl_dcf.hpp"

namespace advee::canopen::ctl {

void describe_dcf(CLI::App& app, DcfArgs& a) {
  auto* dcf = app.add_subcommand("dcf", "configure a node from its device description (CiA 306 DCF/EDS, or a concise DCF)");
  dcf->require_subcommand(1, 1);
  dcf->fallthrough();
  auto* download = dcf->add_subcommand(
      "download", "boot NODE as a manager does (CiA 302-2): check 0x1000 and 0x1018 against FILE (nothing is written "
                  "to a node that is another device), enter pre-operational, download every ParameterValue (PDOs in "
                  "an order that lets the node remap), NMT start. A concise DCF (binary, CiA 302-3) is downloaded "
                  "without identity check.");
  download->add_option("node", a.node, "node-ID (1..127); evaluates $NODEID in FILE")->required();
  download->add_option("file", a.file, "DCF, EDS or concise DCF")->required();
  download->add_flag("--no-start", a.no_start, "leave the node pre-operational");
  download->add_option("--attempts", a.attempts, "tries per SDO transfer that times out")
      ->check(CLI::Range(1u, 100u))
      ->capture_default_str();
  auto* concise = dcf->add_subcommand("concise", "write OUT, the concise DCF of FILE's configuration (no bus I/O)");
  concise->add_option("node", a.node, "node-ID (1..127); evaluates $NODEID in FILE")->required();
  concise->add_option("file", a.file, "DCF or EDS")->required();
  concise->add_option("out", a.out, "the concise DCF to write")->required();
}

int write_concise(const DcfCommand& c) {
  const std::vector<std::uint8_t> bytes = write_concise_dcf(c.boot.configuration);
  std::ofstream out(c.out, std::ios::binary | std::ios::trunc);
  if (out) out.write(reinterpret_cast<const char*>(bytes.data()), static_cast<std::streamsize>(bytes.size()));
  if (out) out.close();
  if (!out) {
    std::fprintf(stderr, "advee-canopenctl: dcf concise: %s: %s\n", c.out.c_str(), std::strerror(errno));
    return cli::kExitFailure;
  }
  std::printf("%s: %zu objects, %zu bytes\n", c.out.c_str(), c.boot.configuration.size(), bytes.size());
  return 0;
}

std::unique_ptr<NodeBoot> run_dcf_download(Master& master, const DcfCommand& c, std::function<void(int)> end) {
  auto boot = std::make_unique<NodeBoot>(master, c.boot);
  const NodeBoot* b = boot.get();
  boot->boot([&c, b, end = std::move(end)](std::error_code ec, const std::string& error) {
    if (ec) {
      std::fprintf(stderr, "advee-canopenctl: dcf download: %s\n", error.c_str());
      return end(cli::kExitFailure);
    }
    std::printf("%s\n", describe_download(c, b->retries()).c_str());
    end(0);
  });
  return boot;
}

}  // namespace advee::canopen::ctl
