// SPDX-License-Identifier: GPL-2.0
// A hwmon device found by its `name` attribute (the hwmonN number changes
// with probe order) and its attributes read the way the hwmon ABI defines
// them (Documentation/hwmon/sysfs-interface.rst): integers, temperatures in
// millidegrees Celsius, fan speeds in RPM.
#pragma once

#include <filesystem>
#include <optional>
#include <string>
#include <vector>

namespace advee::driver_aux {

class HwmonDevice {
 public:
  // The first <root>/hwmonN whose name file reads `name`; nullopt if none.
  static std::optional<HwmonDevice> find(const std::filesystem::path& root, const std::string& name);
  explicit HwmonDevice(std::filesystem::path dir) : dir_(std::move(dir)) {}

  const std::filesystem::path& dir() const { return dir_; }
  bool has(const std::string& attr) const;
  // The integer value of attr; nullopt when the read fails with ENODATA
  // (e.g. a disabled tachometer) or the file is missing. Throws
  // std::system_error for other failures (device gone: ENODEV, EIO).
  std::optional<long> read(const std::string& attr) const;
  // Throws std::system_error.
  void write(const std::string& attr, long value) const;
  // Channels that have <prefix>N_input, e.g. "temp" -> {"temp1", "temp2"}.
  std::vector<std::string> channels(const std::string& prefix) const;

 private:
  std::filesystem::path dir_;
};

}  // namespace advee::driver_aux
