// SPDX-License-Identifier: GPL-2.0
// Boot of one configured node in the manner of CiA 302-2: check the device
// type (0x1000) and identity (0x1018) before anything is written; on a
// mismatch stop with both values in the error (nothing written, no NMT
// command to the node); else enter pre-operational, download the
// configuration (a DCF's ParameterValue objects, PDOs in the order CiA 301
// allows remapping) and start the node. Each SDO transfer that times out is
// repeated; an abort from the device ends the boot.
#pragma once

#include <array>
#include <cstdint>
#include <functional>
#include <initializer_list>
#include <optional>
#include <string>
#include <system_error>
#include <vector>

#include "advee/canopen/device_description.hpp"
#include "advee/canopen/lifetime.hpp"
#include "advee/canopen/master.hpp"
#include "advee/canopen/pdo.hpp"
#include "advee/canopen/sdo_sequence.hpp"

namespace advee::canopen {

enum class BootError {
  kWrongDevice = 1,  // 0x1000 or 0x1018 is not what the configuration expects
};
const std::error_category& boot_category();
inline std::error_code make_error_code(BootError e) { return {static_cast<int>(e), boot_category()}; }

struct NodeBootConfig {
  std::uint8_t node = 1;
  std::string name = "node";  // in messages
  std::optional<std::uint32_t> device_type;  // 0x1000; unset: not checked
  // 0x1018:1..4 vendor-ID, product code, revision number, serial number; unset: not checked.
  std::array<std::optional<std::uint32_t>, 4> identity{};
  std::vector<SdoWrite> configuration;  // downloaded in this order
  // Every PDO the description maps (its ParameterValues, else its defaults),
  // valid or not: the drive drivers take their layouts from here (find_pdo()).
  std::vector<PdoMapping> pdos;
  unsigned sdo_attempts = 3;            // per transfer, counting the first
  bool start = true;                    // NMT start at the end
};

// From a DCF (or an EDS): the device type and vendor, product and revision
// as 0x1000 and 0x1018:1..3 give them (0 is not checked); the serial number
// only where the file gives 0x1018:4 a ParameterValue (an EDS's default says
// nothing about one device). The configuration: every writable entry with a
// ParameterValue; PDO communication and mapping objects in the order that
// lets a device remap: COB-ID invalid, mapping count 0, mapped objects,
// mapping count, the other communication entries, the COB-ID.
NodeBootConfig boot_config_from_dcf(const DeviceDescription& dcf, std::string name);

// The first PDO of this kind that maps every one of the objects (sub-index 0);
// nullptr if none does.
const PdoMapping* find_pdo(const std::vector<PdoMapping>& pdos, PdoKind kind,
                           std::initializer_list<std::uint16_t> objects);

class NodeBoot {
 public:
  // error is empty on success, else says what failed, e.g. "epos (node 1):
  // wrong device: 0x1018:2 product code expected 0x64200000, found 0x64200001".
  using Done = std::function<void(std::error_code, const std::string& error)>;

  NodeBoot(Master& master, NodeBootConfig cfg) : master_(master), cfg_(std::move(cfg)) {}
  NodeBoot(const NodeBoot&) = delete;
  NodeBoot& operator=(const NodeBoot&) = delete;

  // A boot started while another runs cancels that one (its done is not called).
  void boot(Done done);
  bool booted() const { return booted_; }
  const std::string& error() const { return error_; }
  const std::string& reason() const { return reason_; }  // error() without "name (node N): boot failed: "
  const NodeBootConfig& config() const { return cfg_; }
  unsigned retries() const { return retries_; }  // timed-out transfers repeated, over all boots

 private:
  // Runs op, again while it times out, up to cfg_.sdo_attempts times.
  void with_retry(std::function<void(SdoCallback)> op, SdoCallback done, unsigned attempt = 1);
  void check_identity(std::size_t i);
  void download(std::size_t i);
  void fail(std::error_code ec, const std::string& why);

  Master& master_;
  NodeBootConfig cfg_;
  Done done_;
  std::string error_;
  std::string reason_;
  std::string mismatch_;
  bool booted_ = false;
  unsigned retries_ = 0;
  Lifetime lifetime_;  // SDO answers of an earlier boot (or after destruction) do nothing
};

}  // namespace advee::canopen

template <>
struct std::is_error_code_enum<advee::canopen::BootError> : std::true_type {};
