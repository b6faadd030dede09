// SPDX-License-Identifier: GPL-2.0
#include "advee/driver_aux/gpio_input.hpp"

#include <gpiod.h>

#include <cerrno>
#include <system_error>

namespace advee::driver_aux {

void GpioInput::ChipCloser::operator()(gpiod_chip* c) const {
  if (c) gpiod_chip_close(c);
}

GpioInput::GpioInput(gpiod_chip* chip, gpiod_line* line, bool active_low,
                     const std::string& consumer, std::string description)
    : chip_(chip), line_(line), description_(std::move(description)) {
  const int flags = active_low ? GPIOD_LINE_REQUEST_FLAG_ACTIVE_LOW : 0;
  if (gpiod_line_request_input_flags(line_, consumer.c_str(), flags) < 0)
    throw std::system_error(errno, std::generic_category(), "request " + description_);
}

GpioInput GpioInput::by_name(const std::string& line_name, bool active_low,
                             const std::string& consumer) {
  errno = 0;
  gpiod_line* line = gpiod_line_find(line_name.c_str());
  if (!line)
    throw std::system_error(errno ? errno : ENOENT, std::generic_category(),
                            "no GPIO line named " + line_name);
  gpiod_chip* chip = gpiod_line_get_chip(line);
  return GpioInput(chip, line, active_low, consumer,
                   "GPIO line " + line_name + " (" + gpiod_chip_name(chip) + " offset " +
                       std::to_string(gpiod_line_offset(line)) + ")");
}

GpioInput GpioInput::by_offset(const std::string& chip_name, unsigned offset, bool active_low,
                               const std::string& consumer) {
  gpiod_chip* chip = gpiod_chip_open_lookup(chip_name.c_str());
  if (!chip) throw std::system_error(errno, std::generic_category(), "no GPIO chip " + chip_name);
  gpiod_line* line = gpiod_chip_get_line(chip, offset);
  if (!line) {
    const int e = errno;
    gpiod_chip_close(chip);
    throw std::system_error(e, std::generic_category(),
                            "GPIO chip " + chip_name + " has no line " + std::to_string(offset));
  }
  return GpioInput(chip, line, active_low, consumer,
                   "GPIO " + chip_name + " offset " + std::to_string(offset));
}

bool GpioInput::asserted() const {
  const int v = gpiod_line_get_value(line_);
  if (v < 0) throw std::system_error(errno, std::generic_category(), "read " + description_);
  return v == 1;
}

}  // namespace advee::driver_aux
