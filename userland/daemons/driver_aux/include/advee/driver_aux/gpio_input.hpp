// SPDX-License-Identifier: GPL-2.0
// One GPIO line requested as an input through libgpiod (character device),
// found by line name (e.g. DIO_7 of the ts7800-dio chip) or by chip and
// offset. Released on destruction.
#pragma once

#include <memory>
#include <string>

struct gpiod_chip;
struct gpiod_line;

namespace advee::driver_aux {

class GpioInput {
 public:
  // Throws std::system_error (errno: ENOENT for an unknown name or chip,
  // EBUSY when another consumer holds the line).
  static GpioInput by_name(const std::string& line_name, bool active_low, const std::string& consumer);
  static GpioInput by_offset(const std::string& chip, unsigned offset, bool active_low,
                             const std::string& consumer);

  // The logical value (1 = asserted, honouring active_low). Throws std::system_error.
  bool asserted() const;
  const std::string& description() const { return description_; }

 private:
  struct ChipCloser {
    void operator()(gpiod_chip* c) const;
  };
  GpioInput(gpiod_chip* chip, gpiod_line* line, bool active_low, const std::string& consumer,
            std::string description);
  std::unique_ptr<gpiod_chip, ChipCloser> chip_;  // closing the chip releases the line
  gpiod_line* line_;
  std::string description_;
};

}  // namespace advee::driver_aux
