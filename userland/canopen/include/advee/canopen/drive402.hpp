// SPDX-License-Identifier: GPL-2.0
// One CiA 402 drive on the master: boot (heartbeats both ways, PDO mapping
// read back and verified or remapped, PDOs enabled, NMT start), the power
// state machine (Axis402), mode changes (halt cleared first, then wait for
// 0x6061), profile velocity, profile position with the set-point handshake,
// homing, and reports of EMCY, heartbeat loss and reboots. Only PDOs are used
// once the drive runs; SDO is for boot and mode changes.
#pragma once

#include <cstdint>
#include <functional>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "advee/canopen/axis402.hpp"
#include "advee/canopen/lifetime.hpp"
#include "advee/canopen/master.hpp"
#include "advee/canopen/node_boot.hpp"
#include "advee/canopen/pdo.hpp"

namespace advee::canopen {

struct DriveConfig {
  std::uint8_t node = 1;
  std::string name = "drive";
  // The RPDO that carries the controlword and the set-point, and the TPDO
  // that carries the statusword and the feedback, as the driver needs them.
  unsigned control_rpdo = 1;
  std::vector<PdoEntry> control_entries;
  unsigned status_tpdo = 1;
  std::vector<PdoEntry> status_entries;
  // If the device maps something else: remap it (true) or fail the boot.
  bool remap_if_different = false;
  std::uint16_t heartbeat_ms = 100;          // drive produces (0x1017)
  std::uint16_t master_heartbeat_timeout_ms = 500;  // drive consumes the master (0x1016)
  unsigned heartbeat_tolerance = 3;           // master: lost after this many periods
  Duration sdo_timeout = std::chrono::milliseconds(500);
  AxisConfig axis;
  Duration mode_timeout = std::chrono::seconds(1);
  Duration setpoint_timeout = std::chrono::milliseconds(500);
  Duration move_timeout = std::chrono::seconds(30);
  Duration homing_timeout = std::chrono::seconds(30);
  // The device this node must be and its configuration (boot_config_from_dcf()
  // of its DCF or EDS): when set, boot() first runs that CiA 302-2 check and
  // download (NodeBoot; node and name from here, its NMT start left to the
  // end of this boot), and a wrong device is refused before any write.
  std::optional<NodeBootConfig> device = std::nullopt;
};

// A drive driver's PDO layout from its device description: when d.device is
// set and maps an RPDO with every object of `control` (a TPDO with every
// object of `status`), that PDO's number and entries replace the driver's
// built-in choice, which stays for a drive without a description.
void take_pdos_from_device(DriveConfig& d, std::initializer_list<std::uint16_t> control,
                           std::initializer_list<std::uint16_t> status);

enum class DriveEventKind { kEmcy, kHeartbeatLost, kHeartbeatResumed, kRebooted, kFault };
struct DriveEvent {
  DriveEventKind kind;
  std::uint8_t node;
  std::uint16_t emcy_code = 0;
  std::string text;
};

class Drive402 final : public TimedService {
 public:
  using Done = std::function<void(std::error_code)>;

  Drive402(Master& master, DriveConfig cfg);
  Drive402(const Drive402&) = delete;
  Drive402& operator=(const Drive402&) = delete;

  void boot(Done done);
  bool booted() const { return booted_; }
  // Why the last boot failed, e.g. "epos (node 1): boot failed: control RPDO:
  // device PDO mapping is not what the driver needs (device has RPDO2 0x301
  // type 255: 6040:00/16 6060:00/8, driver needs 6040:00/16 60FF:00/32)".
  const std::string& boot_error() const { return boot_error_; }

  void enable(Done done) { axis_.request(cia402::State::kOperationEnabled, std::move(done)); }
  void disable(Done done) { axis_.request(cia402::State::kSwitchOnDisabled, std::move(done)); }
  void quick_stop(Done done) { axis_.request(cia402::State::kQuickStopActive, std::move(done)); }

  // Clears halt, writes 0x6060, then reads 0x6061 until it matches.
  void set_mode(cia402::Mode mode, Done done);
  std::optional<cia402::Mode> mode() const { return mode_; }

  // Sets one mapped object of the control RPDO (e.g. 0x60FF) and sends it.
  bool set_target(std::uint16_t index, std::uint8_t sub, std::int64_t value);
  void halt(bool on) { axis_.set_bits(cia402::cw::kHalt, on ? cia402::cw::kHalt : 0); }
  // Profile position: target, new set-point, wait for the acknowledge, drop
  // the bit, then done when target reached (bit 10).
  void move_to(std::int32_t position, bool relative, Done done);
  // Homing mode must be active: rising edge on bit 4, done on attained + reached.
  void home(Done done);

  // Last value of a mapped feedback object (from the status TPDO).
  std::optional<std::int64_t> feedback(std::uint16_t index, std::uint8_t sub = 0) const;
  Axis402& axis() { return axis_; }
  SdoClient& sdo() { return master_.sdo(cfg_.node); }
  const DriveConfig& config() const { return cfg_; }
  const PdoMapping& control_mapping() const { return control_map_; }
  const PdoMapping& status_mapping() const { return status_map_; }
  std::uint64_t status_frames() const { return status_frames_; }

  void on_event(std::function<void(const DriveEvent&)> cb) { listeners_.push_back(std::move(cb)); }

  void poll() override;
  std::optional<TimePoint> deadline() const override;

 private:
  enum class Motion { kNone, kModeWait, kSetPoint, kMoving, kHoming };
  void send_control();
  void on_status(const CanFrame& f);
  void emit(DriveEvent e);
  void configure_pdo(PdoKind kind, unsigned number, const std::vector<PdoEntry>& need,
                     std::function<void(std::error_code, const PdoMapping&)> done);
  void finish_motion(std::error_code ec);
  void read_mode_display();
  void boot_failed(const std::string& why, std::error_code ec);
  void boot_driver();

  Master& master_;
  DriveConfig cfg_;
  Axis402 axis_;
  PdoMapping control_map_;
  PdoMapping status_map_;
  std::optional<PdoCodec> control_codec_;
  std::optional<PdoCodec> status_codec_;
  CanFrame control_frame_;
  std::optional<CanFrame> last_status_;
  Registration service_;
  Registration status_sub_;
  Registration emcy_listener_;
  Registration hb_listener_;
  bool booted_ = false;
  bool booting_ = false;
  Done boot_done_;
  std::unique_ptr<NodeBoot> device_boot_;  // this boot's, while cfg_.device is set
  std::string boot_error_;
  std::string mismatch_;
  std::optional<cia402::Mode> mode_;
  Motion motion_ = Motion::kNone;
  Done motion_done_;
  TimePoint motion_deadline_{};
  cia402::Mode wanted_mode_ = cia402::Mode::kNone;
  std::optional<TimePoint> next_mode_read_;
  bool mode_read_pending_ = false;
  std::uint64_t status_frames_ = 0;
  std::vector<std::function<void(const DriveEvent&)>> listeners_;
  // Every SDO completion this driver queues is wrapped with one of these: the
  // SdoClient belongs to the master and may answer after the driver is gone.
  // The boot's is renewed by boot() and by a reboot during boot, so the
  // answers of an abandoned boot are dropped too.
  Lifetime lifetime_;
  Lifetime boot_lifetime_;
};

}  // namespace advee::canopen
