// SPDX-License-Identifier: GPL-2.0
#include "advee/rs485_daemon/bus_section.hpp"

#include <cmath>

namespace advee::rs485_daemon {

BusSection parse_bus_section(const module::ConfigNode& b, const std::optional<std::string>& default_device) {
  b.allow_only({"device", "baud", "timeout_ms", "retries"});
  BusSection s;
  s.device = default_device ? b.get<std::string>("device", *default_device) : b.get<std::string>("device");
  if (s.device.empty()) b.fail("device", "must name a device (a path or a bus name such as a)");
  s.config.baud = b.get<std::uint32_t>("baud", s.config.baud);
  if (s.config.baud < 300 || s.config.baud > 4000000) b.fail("baud", "must be 300..4000000");
  const double default_ms = std::chrono::duration<double, std::milli>(s.config.timeout).count();
  const double ms = b.get<double>("timeout_ms", default_ms);
  if (!(ms >= 0.1 && ms <= 10000)) b.fail("timeout_ms", "must be 0.1..10000");
  s.config.timeout = std::chrono::microseconds(std::llround(ms * 1000));
  s.config.retries = b.get<std::uint32_t>("retries", s.config.retries);
  if (s.config.retries > 16) b.fail("retries", "must be 0..16");
  return s;
}

}  // namespace advee::rs485_daemon
