// SPDX-License-Identifier: GPL-2.0
#include "canopenctl_dcf.hpp"

#include <cerrno>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <iterator>
#include <vector>

#include "advee/canopen/concise_dcf.hpp"
#include "advee/canopen/device_description.hpp"
#include "canopenctl_text.hpp"

namespace advee::canopen::ctl {

namespace {

std::vector<std::uint8_t> read_file(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw FileError(path + ": " + std::strerror(errno));
  std::vector<std::uint8_t> bytes{std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
  if (in.bad()) throw FileError(path + ": read error");
  return bytes;
}

std::string base_name(const std::string& path) {
  const auto slash = path.rfind('/');
  return slash == std::string::npos ? path : path.substr(slash + 1);
}

std::string hex32(std::uint32_t v) {
  char b[12];
  std::snprintf(b, sizeof b, "0x%08X", v);
  return b;
}

}  // namespace

DcfCommand check_dcf(const std::string& name, const DcfArgs& a) {
  DcfCommand c;
  c.name = name;
  c.file = a.file;
  c.out = a.out;
  const std::uint8_t node = parse_node(a.node);
  const std::vector<std::uint8_t> bytes = read_file(a.file);
  if (looks_like_concise_dcf(bytes)) {
    if (name == "dcf concise") throw UsageError(a.file + " is a concise DCF already; give a DCF or EDS");
    ConciseDcfResult r = parse_concise_dcf(bytes);
    if (!r.ok()) throw FileError(a.file + ": not a valid concise DCF: " + r.error);
    c.concise_input = true;
    c.boot.configuration = std::move(r.writes);
    c.boot.name = base_name(a.file);
  } else {
    const std::string text(bytes.begin(), bytes.end());
    DescriptionResult r = parse_device_description(text, a.file, node);
    if (!r.description) {
      std::string all;
      for (const DescriptionError& e : r.errors) all += (all.empty() ? "" : "\n") + e.text();
      throw FileError(all.empty() ? a.file + ": not a device description" : all);
    }
    const auto node_name = DeviceDescription::value(r.description->commissioning, "NodeName");
    c.boot = boot_config_from_dcf(*r.description, node_name && !node_name->empty() ? *node_name : base_name(a.file));
  }
  c.boot.node = node;
  c.boot.start = !a.no_start;
  c.boot.sdo_attempts = a.attempts;
  return c;
}

std::string describe_download(const DcfCommand& c, unsigned retries) {
  const NodeBootConfig& b = c.boot;
  std::string s = "node " + std::to_string(b.node) + " (" + b.name + "): " + std::to_string(b.configuration.size()) +
                  (b.configuration.size() == 1 ? " object" : " objects") + " written, ";
  static const char* const kNames[] = {"vendor", "product", "revision", "serial"};
  std::string checked;
  if (b.device_type) checked = "device type " + hex32(*b.device_type);
  for (std::size_t i = 0; i < b.identity.size(); ++i)
    if (b.identity[i]) checked += (checked.empty() ? "" : ", ") + std::string(kNames[i]) + " " + hex32(*b.identity[i]);
  if (c.concise_input)
    s += "identity not checked (a concise DCF has none)";
  else if (checked.empty())
    s += "identity not checked (the file gives none)";
  else
    s += "identity checked (" + checked + ")";
  if (retries) s += ", " + std::to_string(retries) + " timed-out transfers repeated";
  return s + (b.start ? ", started" : ", left pre-operational");
}

}  // namespace advee::canopen::ctl
