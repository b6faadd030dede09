// SPDX-License-Identifier: GPL-2.0
#include "advee/robotsim/stream_drive.hpp"

#include <fcntl.h>
#include <unistd.h>

#include <cerrno>
#include <cmath>
#include <sstream>
#include <system_error>

#include "advee/robotsim/world.hpp"

namespace advee::robotsim {

DriveCommand parse_drive_line(const std::string& line) {
  std::istringstream in(line);
  double speed = 0, steering_deg = 0;
  std::string extra;
  if (!(in >> speed >> steering_deg) || (in >> extra) || !std::isfinite(speed) || !std::isfinite(steering_deg))
    throw ConfigError("drive input: '" + line + "': expected SPEED_MPS STEERING_DEG");
  return {speed, deg_to_rad(steering_deg)};
}

StreamDrive::StreamDrive(UniqueFd fd) : fd_(std::move(fd)) {
  const int flags = fcntl(fd_.get(), F_GETFL);
  if (flags < 0 || fcntl(fd_.get(), F_SETFL, flags | O_NONBLOCK) < 0)
    throw std::system_error(errno, std::generic_category(), "drive input: fcntl");
}

DriveCommand StreamDrive::command(double) {
  char buf[512];
  while (!eof_) {
    const ssize_t n = read(fd_.get(), buf, sizeof buf);
    if (n > 0) {
      pending_.append(buf, static_cast<std::size_t>(n));
    } else if (n == 0) {
      eof_ = true;
    } else if (errno == EAGAIN || errno == EWOULDBLOCK) {
      break;
    } else if (errno != EINTR) {
      throw std::system_error(errno, std::generic_category(), "drive input: read");
    }
  }
  for (std::size_t nl; (nl = pending_.find('\n')) != std::string::npos;) {
    const std::string line = pending_.substr(0, nl);
    pending_.erase(0, nl + 1);
    if (line.find_first_not_of(" \t\r") == std::string::npos || line[0] == '#') continue;
    last_ = parse_drive_line(line);
  }
  return last_;
}

}  // namespace advee::robotsim
