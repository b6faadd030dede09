// SPDX-License-Identifier: GPL-2.0
#include "canopenctl_lss.hpp"

#include <cstdio>
#include <cstdlib>

#include "canopenctl_text.hpp"

namespace advee::canopen::ctl {

namespace {
std::uint32_t parse_word(const std::string& s, const std::string& whole, const char* what = nullptr) {
  std::string digits = s;
  if (digits.size() > 2 && digits[0] == '0' && (digits[1] == 'x' || digits[1] == 'X')) digits = digits.substr(2);
  if (digits.empty() || digits.size() > 8 || digits.find_first_not_of("0123456789abcdefABCDEF") != std::string::npos)
    throw UsageError(what ? std::string(what) + " '" + whole + "': expected a 32-bit hex number"
                          : "identity '" + whole + "': expected VENDOR:PRODUCT:REVISION:SERIAL, 32-bit hex numbers");
  return static_cast<std::uint32_t>(std::strtoul(digits.c_str(), nullptr, 16));
}
}  // namespace

LssAddress parse_lss_address(const std::string& s) {
  LssAddress a;
  std::size_t start = 0;
  for (int i = 0; i < 4; ++i) {
    const std::size_t colon = s.find(':', start);
    if ((i < 3) != (colon != std::string::npos))
      throw UsageError("identity '" + s + "': expected VENDOR:PRODUCT:REVISION:SERIAL, 32-bit hex numbers");
    a.words[i] = parse_word(s.substr(start, i < 3 ? colon - start : std::string::npos), s);
    start = colon + 1;
  }
  return a;
}

LssCommand check_lss(const std::string& name, const LssArgs& a) {
  LssCommand c;
  c.name = name;
  c.config.timeout = std::chrono::milliseconds(a.answer_ms);
  c.config.settle = std::chrono::milliseconds(a.settle_ms);
  if (a.settle_ms >= a.answer_ms) throw UsageError("--settle-ms must be shorter than --answer-ms");
  c.store = a.store;
  if (name == "lss scan") {
    if (!a.assign.empty()) c.assign = parse_node(a.assign);
    if (c.store && !c.assign) throw UsageError("lss scan: --store needs --assign");
    if (!a.vendor.empty()) c.known[0] = parse_word(a.vendor, a.vendor, "--vendor");
    if (!a.product.empty()) c.known[1] = parse_word(a.product, a.product, "--product");
  } else if (name == "lss set-id") {
    c.node = parse_node(a.node);
    if (!a.identity.empty()) c.identity = parse_lss_address(a.identity);
  } else if (name != "lss identify") {
    throw UsageError("unknown lss command '" + name + "'");
  }
  return c;
}

std::string describe_found(const LssFound& f) {
  std::string s = to_string(f.address);
  if (f.node_id != kLssUnconfigured) s += " node-ID " + std::to_string(f.node_id);
  return s;
}

}  // namespace advee::canopen::ctl
