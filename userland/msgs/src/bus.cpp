// SPDX-License-Identifier: GPL-2.0
#include "advee/msgs/bus.hpp"

#include <arpa/inet.h>
#include <netinet/in.h>
#include <sys/socket.h>
#include <unistd.h>

#include <cerrno>
#include <cstdlib>
#include <cstring>
#include <fstream>

namespace advee::msgs {

const char* const kLcmConfFile = ADVEE_LCM_CONF_FILE;

namespace {

std::string trim(const std::string& s) {
  const auto b = s.find_first_not_of(" \t\r");
  if (b == std::string::npos) return "";
  const auto e = s.find_last_not_of(" \t\r");
  return s.substr(b, e - b + 1);
}

std::string unquote(std::string v) {
  if (v.size() >= 2 && (v.front() == '"' || v.front() == '\'') && v.back() == v.front())
    return v.substr(1, v.size() - 2);
  return v;
}

// The fix for a missing route, in the words of the install (docs/install.md).
constexpr const char* kRouteFix =
    "add a multicast route (the robot: systemd-networkd's 80-advee-lcm.network; by hand: "
    "ip route add 224.0.0.0/4 dev IFACE)";

}  // namespace

std::string url_in_conf_file(const std::string& path) {
  std::ifstream in(path);
  std::string line, url;
  const std::string key = std::string(kLcmUrlVariable) + "=";
  while (std::getline(in, line)) {
    line = trim(line);
    if (line.rfind("export ", 0) == 0) line = trim(line.substr(7));
    if (line.rfind(key, 0) == 0) url = unquote(trim(line.substr(key.size())));
  }
  return url;
}

BusUrl bus_url(const std::string& given, const std::string& given_from, const std::string& conf_file) {
  if (!given.empty()) return {given, given_from};
  if (const char* env = std::getenv(kLcmUrlVariable); env && *env) return {env, kLcmUrlVariable};
  if (auto url = url_in_conf_file(conf_file); !url.empty()) return {url, conf_file};
  return {kLcmBuiltinUrl, "LCM's default"};
}

std::string multicast_route_problem(const std::string& url) {
  const std::string scheme = "udpm://";
  if (url.rfind(scheme, 0) != 0) return "";
  const auto end = url.find_first_of(":?", scheme.size());
  const std::string group = url.substr(scheme.size(), end == std::string::npos ? std::string::npos : end - scheme.size());
  sockaddr_in to{};
  to.sin_family = AF_INET;
  to.sin_port = htons(7667);  // the port does not take part in routing
  if (inet_pton(AF_INET, group.c_str(), &to.sin_addr) != 1)
    return "LCM URL " + url + ": " + group + " is not an IPv4 multicast group";
  const int fd = socket(AF_INET, SOCK_DGRAM | SOCK_CLOEXEC, 0);
  if (fd < 0) return "";  // no socket at all: LCM's own start-up reports it
  // connect() on a UDP socket only looks the route up: no packet is sent.
  const int rc = connect(fd, reinterpret_cast<const sockaddr*>(&to), sizeof to);
  const int err = errno;
  close(fd);
  if (rc == 0) return "";
  return "no route to the LCM multicast group " + group + " (" + std::strerror(err) + "): " + kRouteFix;
}

std::unique_ptr<lcm::LCM> open_bus(const BusUrl& url) {
  const std::string where = "LCM URL " + url.url + " (from " + url.from + ")";
  if (auto problem = multicast_route_problem(url.url); !problem.empty())
    throw BusUnavailable(problem + "; " + where);
  auto lcm = std::make_unique<lcm::LCM>(url.url);
  if (!lcm->good())
    throw BusUnavailable("LCM did not start on " + where +
                         ": its socket set-up or multicast self-test failed (is the interface up with "
                         "MULTICAST, does a firewall drop UDP to the group?)");
  return lcm;
}

}  // namespace advee::msgs
