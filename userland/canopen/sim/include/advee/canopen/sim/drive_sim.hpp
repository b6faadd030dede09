// SPDX-License-Identifier: GPL-2.0
// A simulated CiA 402 drive: object dictionary, SDO server, NMT slave,
// heartbeat producer and consumer, PDOs per the mapping in its dictionary,
// the 402 power state machine and simple velocity/position/homing dynamics.
// Profiles follow what canopen-notes.md §3.12-3.14 says about the EPOS 70/10
// (classic DSP 402 PDO set, TxPDO4 disabled) and the IclA (second PDO
// convention: RPDO2 = controlword + target position). Passive like the
// master: handle(), poll(), deadline().
#pragma once

#include <array>
#include <cstdint>
#include <optional>
#include <string>
#include <string_view>

#include "advee/canopen/cia402.hpp"
#include "advee/canopen/clock.hpp"
#include "advee/canopen/frame.hpp"
#include "advee/canopen/nmt.hpp"
#include "advee/canopen/pdo.hpp"
#include "advee/canopen/object_dictionary.hpp"
#include "advee/canopen/sdo_server.hpp"

namespace advee::canopen::sim {

enum class DriveProfile { kEpos, kIcla };

struct DriveFaults {
  bool heartbeat_silent = false;               // no heartbeat, no node-guarding replies
  bool refuse_mode_change_while_halt = false;  // 0x6061 ignores 0x6060 while halt is set
  bool ignore_mode_change = false;             // 0x6061 never follows 0x6060
  bool refuse_transition_16 = false;           // quick stop active -> operation enabled refused
  bool homing_switch_missing = false;          // homing runs into an error
};

struct DriveSimConfig {
  std::uint8_t node = 1;
  DriveProfile profile = DriveProfile::kEpos;
  // Position units per second that one velocity unit moves (EPOS: rpm ->
  // encoder counts of a 500-line encoder at 4x: 2000/60).
  double position_per_velocity = 2000.0 / 60.0;
  double home_switch_position = -3000;  // where the home switch sits
  // A mechanical home switch: where travel() (the shaft's displacement since
  // power-on, kept across homing and NMT resets) meets it; when set, it
  // replaces home_switch_position. For a drive coupled to a mechanism
  // (advee-robot-sim's steering), whose switch does not move when the drive's
  // position counter is re-referenced.
  std::optional<double> home_switch_travel = std::nullopt;
  std::int32_t home_offset = 0;  // 0x607C at power-on: the position homing sets at the switch (replaces the EDS's)
  std::uint32_t serial = 0;  // 0x1018:4, serial number; 0: the EDS's ($NODEID, the node-ID)
  Duration step = std::chrono::milliseconds(1);
  // The device description (EDS) the dictionary is built from; empty: the
  // profile's shipped one (data/*.eds, built in: shipped_eds()). The
  // constructor throws std::runtime_error with the parse errors of a bad one.
  std::string eds_file = {};
};

// The shipped EDS of a profile (userland/canopen/data) and its file name.
std::string_view shipped_eds(DriveProfile profile);
std::string_view shipped_eds_name(DriveProfile profile);

class SimulatedDrive {
 public:
  SimulatedDrive(DriveSimConfig cfg, FrameSender send, NowFn now);
  SimulatedDrive(const SimulatedDrive&) = delete;
  SimulatedDrive& operator=(const SimulatedDrive&) = delete;

  // Power-on: boot-up message, pre-operational.
  void power_on();
  void handle(const CanFrame& f);
  void poll();
  std::optional<TimePoint> deadline() const;

  // Fault injection: EMCY with `code`, fault reaction, then fault.
  void inject_fault(std::uint16_t emcy_code);

  ObjectDictionary& od() { return od_; }
  SdoServer& sdo() { return sdo_; }
  DriveFaults& faults() { return faults_; }
  const DriveSimConfig& config() const { return cfg_; }
  cia402::State state() const { return state_; }
  NmtState nmt_state() const { return nmt_; }
  double position() const { return pos_; }
  double velocity() const { return vel_; }
  // Displacement of the shaft since construction, in position units: what
  // the mechanism moved, unlike position() it does not jump on homing or reset.
  double travel() const { return travel_; }
  std::uint64_t rpdos_received() const { return rpdos_received_; }
  std::uint64_t tpdos_sent() const { return tpdos_sent_; }

 private:
  void build_dictionary();
  void install_validators();
  void enter_nmt(NmtState s);
  void reset(bool application);
  void on_nmt(const CanFrame& f);
  void on_sync(const CanFrame& f);
  bool on_rpdo(const CanFrame& f);
  void on_master_heartbeat();
  void apply_rpdo(unsigned n, const CanFrame& f);
  void process_controlword();
  void set_state(cia402::State s);
  void update_statusword();
  void step(double dt);
  void service_tpdos(bool sync, std::uint8_t sync_counter = 0);
  void send_emcy(std::uint16_t code, std::uint8_t reg);
  void check_master_heartbeat(TimePoint now);
  std::int8_t mode() const { return od_.get<std::int8_t>(0x6061); }

  DriveSimConfig cfg_;
  FrameSender send_;
  NowFn now_;
  ObjectDictionary od_;
  ObjectDictionary defaults_;
  SdoServer sdo_;
  DriveFaults faults_;

  NmtState nmt_ = NmtState::kBootUp;
  cia402::State state_ = cia402::State::kNotReadyToSwitchOn;
  std::uint16_t prev_cw_ = 0;
  double pos_ = 0;
  double vel_ = 0;
  double travel_ = 0;
  // pp
  bool setpoint_ack_ = false;
  bool moving_ = false;
  double target_pos_ = 0;
  // hm
  bool homing_active_ = false;
  bool homing_attained_ = false;
  bool homing_error_ = false;
  double homing_start_ = 0;
  double homing_start_travel_ = 0;

  TimePoint last_step_{};
  TimePoint next_heartbeat_{};
  std::optional<TimePoint> master_hb_seen_;
  bool master_hb_lost_ = false;

  struct TpdoState {
    std::optional<CanFrame> last;
    TimePoint last_sent{};
    unsigned sync_count = 0;
  };
  // Mapping + codec per TPDO, rebuilt only when 0x1800-0x1803/0x1A00-0x1A03 change.
  struct TpdoCache {
    PdoMapping mapping;
    std::optional<PdoCodec> codec;
    std::uint16_t inhibit_100us = 0;
    std::uint16_t event_timer_ms = 0;
  };
  void refresh_tpdo_cache();
  bool dynamic() const;
  std::array<TpdoCache, 4> tpdo_cache_{};
  bool tpdo_cache_valid_ = false;
  std::optional<TimePoint> tpdo_due_;  // an inhibited change or an event timer
  std::array<TpdoState, 4> tpdo_{};
  std::array<std::optional<CanFrame>, 4> rpdo_latched_{};  // synchronous RPDOs wait for SYNC
  bool guard_toggle_ = false;  // node guarding reply toggle, 0 after reset
  std::uint64_t rpdos_received_ = 0;
  std::uint64_t tpdos_sent_ = 0;
};

}  // namespace advee::canopen::sim
