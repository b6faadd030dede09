// SPDX-License-Identifier: GPL-2.0
#include "advee/rs485sim/control_client.hpp"

#include <poll.h>
#include <sys/socket.h>
#include <sys/un.h>

#include <cerrno>
#include <cstring>
#include <stdexcept>
#include <system_error>

#include "advee/unique_fd.hpp"

namespace advee::rs485sim {

std::string control_request(const std::string& socket_path, const std::string& command,
                            std::chrono::milliseconds timeout) {
  UniqueFd fd(socket(AF_UNIX, SOCK_DGRAM | SOCK_CLOEXEC, 0));
  if (!fd) throw std::system_error(errno, std::generic_category(), "control socket");
  // Autobind to an abstract address so that the simulator can reply.
  const sa_family_t family = AF_UNIX;
  if (bind(fd.get(), reinterpret_cast<const sockaddr*>(&family), sizeof(family)))
    throw std::system_error(errno, std::generic_category(), "control socket bind");
  sockaddr_un a{};
  a.sun_family = AF_UNIX;
  if (socket_path.size() >= sizeof(a.sun_path))
    throw std::system_error(ENAMETOOLONG, std::generic_category(), socket_path);
  std::memcpy(a.sun_path, socket_path.c_str(), socket_path.size() + 1);
  if (sendto(fd.get(), command.data(), command.size(), 0, reinterpret_cast<const sockaddr*>(&a), sizeof(a)) < 0)
    throw std::system_error(errno, std::generic_category(), socket_path + " (is advee-rs485-sim running?)");
  pollfd p{fd.get(), POLLIN, 0};
  const int n = poll(&p, 1, static_cast<int>(timeout.count()));
  if (n < 0) throw std::system_error(errno, std::generic_category(), "control socket poll");
  if (n == 0) throw std::system_error(ETIMEDOUT, std::generic_category(), "no reply from " + socket_path);
  char buf[8192];
  const ssize_t len = recv(fd.get(), buf, sizeof(buf), 0);
  if (len < 0) throw std::system_error(errno, std::generic_category(), "control socket recv");
  return std::string(buf, static_cast<std::size_t>(len));
}

std::string control_ok(const std::string& socket_path, const std::string& command) {
  auto reply = control_request(socket_path, command);
  if (reply.rfind("ok", 0) != 0) throw std::runtime_error("'" + command + "': " + reply);
  return reply;
}

}  // namespace advee::rs485sim
