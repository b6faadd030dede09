// SPDX-License-Identifier: GPL-2.0
// The LCM bus of the robot: which URL a program uses, and opening it with one
// error line that names the fix when multicast cannot work (issue 21,
// docs/modules.md "LCM URL", docs/install.md "Two computers").
//
// The URL, first found wins:
//   1. the program's own setting (--lcm, --url, module.lcm_url);
//   2. the environment variable LCM_DEFAULT_URL (LCM's own, which Debian's
//      lcm-spy and lcm-logger read too);
//   3. LCM_DEFAULT_URL= in /etc/advee/lcm.conf, the one place an installed
//      robot keeps it (an environment file: `set -a; . /etc/advee/lcm.conf`
//      gives a shell the same URL for LCM's own tools);
//   4. LCM's built-in default.
#pragma once

#include <lcm/lcm-cpp.hpp>

#include <memory>
#include <stdexcept>
#include <string>

namespace advee::msgs {

// /etc/advee/lcm.conf (the installed conf/lcm.conf; CMake's sysconfdir).
extern const char* const kLcmConfFile;
inline constexpr const char* kLcmUrlVariable = "LCM_DEFAULT_URL";
// What liblcm uses when nothing is set (lcm.c); named here for messages only.
inline constexpr const char* kLcmBuiltinUrl = "udpm://239.255.76.67:7667?ttl=0";

struct BusUrl {
  std::string url;   // never empty
  std::string from;  // where it came from, for messages: "--lcm", "LCM_DEFAULT_URL", the file, "LCM's default"
};

// `given`: the program's own setting ("" = none), named `given_from` in messages.
BusUrl bus_url(const std::string& given, const std::string& given_from = "--lcm",
               const std::string& conf_file = kLcmConfFile);

// The value of LCM_DEFAULT_URL in an environment file ("" when the file or
// the line is missing). Lines KEY=VALUE, # comments, optional quotes.
std::string url_in_conf_file(const std::string& path);

// Why a udpm:// URL cannot reach its group from this host, or "" when the
// kernel has a route to it (other providers: always ""). One line naming the
// fix.
std::string multicast_route_problem(const std::string& url);

class BusUnavailable : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

// The bus for `url`; throws BusUnavailable with one line naming the fix: no
// multicast route, or LCM's own start-up (socket, self-test) failing.
std::unique_ptr<lcm::LCM> open_bus(const BusUrl& url);

}  // namespace advee::msgs
