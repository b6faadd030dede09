// SPDX-License-Identifier: GPL-2.0
#include "advee/driver_aux/hwmon.hpp"

#include <fcntl.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <cstdlib>
#include <fstream>
#include <system_error>

namespace advee::driver_aux {

namespace fs = std::filesystem;

std::optional<HwmonDevice> HwmonDevice::find(const fs::path& root, const std::string& name) {
  std::error_code ec;
  std::vector<fs::path> dirs;
  for (const auto& e : fs::directory_iterator(root, ec)) dirs.push_back(e.path());
  std::sort(dirs.begin(), dirs.end());  // hwmon0 before hwmon1: deterministic with two chips
  for (const auto& d : dirs) {
    std::ifstream f(d / "name");
    std::string n;
    if (f && std::getline(f, n) && n == name) return HwmonDevice(d);
  }
  return std::nullopt;
}

bool HwmonDevice::has(const std::string& attr) const { return fs::exists(dir_ / attr); }

std::optional<long> HwmonDevice::read(const std::string& attr) const {
  const auto path = (dir_ / attr).string();
  const int fd = ::open(path.c_str(), O_RDONLY | O_CLOEXEC);
  if (fd < 0) {
    if (errno == ENOENT) return std::nullopt;
    throw std::system_error(errno, std::generic_category(), path);
  }
  char buf[32];
  const ssize_t n = ::read(fd, buf, sizeof buf - 1);
  const int err = errno;
  ::close(fd);
  if (n < 0) {
    if (err == ENODATA) return std::nullopt;
    throw std::system_error(err, std::generic_category(), path);
  }
  buf[n] = '\0';
  char* end = nullptr;
  errno = 0;
  const long v = std::strtol(buf, &end, 10);
  if (end == buf || errno) throw std::system_error(EINVAL, std::generic_category(), path + ": not a number");
  return v;
}

void HwmonDevice::write(const std::string& attr, long value) const {
  const auto path = (dir_ / attr).string();
  const int fd = ::open(path.c_str(), O_WRONLY | O_CLOEXEC);
  if (fd < 0) throw std::system_error(errno, std::generic_category(), path);
  const std::string s = std::to_string(value) + "\n";
  const ssize_t n = ::write(fd, s.data(), s.size());
  const int err = errno;
  ::close(fd);
  if (n != static_cast<ssize_t>(s.size()))
    throw std::system_error(n < 0 ? err : EIO, std::generic_category(), path);
}

std::vector<std::string> HwmonDevice::channels(const std::string& prefix) const {
  std::vector<std::string> out;
  for (int i = 1; i <= 16; ++i) {
    const std::string ch = prefix + std::to_string(i);
    if (has(ch + "_input")) out.push_back(ch);
  }
  return out;
}

}  // namespace advee::driver_aux
