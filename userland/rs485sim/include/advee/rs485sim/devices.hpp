// SPDX-License-Identifier: GPL-2.0
// Behavioural models of the robot's four boards (thesis appendix A; data
// layouts in shared/specs/rs485-protocol.md). Readings are set in physical
// units (metres, degrees, amperes) and encoded as the board would.
#pragma once

#include <array>
#include <map>
#include <memory>
#include <optional>

#include "advee/rs485sim/device.hpp"

namespace advee::rs485sim {

// BR-SD1: 8 SRF-08 ultrasonic and 2 Sharp GP2Y0A41 infrared rangers, PAUSE sources.
class Sd1 final : public Device {
 public:
  static constexpr std::size_t kSrf = 8;
  static constexpr std::size_t kIr = 2;
  static constexpr std::uint8_t kGetSrf = 0x01, kGetIr = 0x02, kGetBoth = 0x10,
                                kGetPauseSrc = 0x20, kClearPauseSrc = 0x21;

  explicit Sd1(std::uint8_t addr) : Device("sd1", addr) {}
  // nullopt = no echo (SRF) / out of range (IR).
  void set_srf(std::size_t i, std::optional<double> metres);
  void set_ir(std::size_t i, std::optional<double> metres);
  // Raise PAUSE sources (bit mask, latched until CLEAR_PAUSE_SRC).
  void raise_pause(std::uint8_t mask) { pause_src_ |= mask; }

  void set(const std::string& key, const std::vector<std::string>& args) override;
  std::string show(Clock::time_point now) const override;

 protected:
  std::optional<Result> execute(std::uint8_t instr, std::span<const std::uint8_t> data,
                                Clock::time_point now) override;
  void reset_state(Clock::time_point) override { pause_src_ = 0; }

 private:
  void append_srf(std::vector<std::uint8_t>& v) const;
  void append_ir(std::vector<std::uint8_t>& v) const;

  std::array<std::uint16_t, kSrf> srf_cm_{};  // 0xffff = no echo
  std::array<std::uint8_t, kIr> ir_half_mm_{};  // 0 = out of range
  std::uint8_t pause_src_ = 0;
};

// BR-SO1: two wheel encoders; the counters wrap in the width the master asks for.
class So1 final : public Device {
 public:
  static constexpr std::uint8_t kGetTicks = 0x01, kResetTicks = 0x02;

  explicit So1(std::uint8_t addr) : Device("so1", addr) {}
  // Ticks since the last reset (left, right) and how fast they grow (ticks/s).
  void set_ticks(std::int64_t left, std::int64_t right, Clock::time_point now);
  void set_rate(double left_per_s, double right_per_s, Clock::time_point now);
  std::array<std::int64_t, 2> ticks(Clock::time_point now) const;

  void set(const std::string& key, const std::vector<std::string>& args) override;
  std::string show(Clock::time_point now) const override;

 protected:
  std::optional<Result> execute(std::uint8_t instr, std::span<const std::uint8_t> data,
                                Clock::time_point now) override;
  void reset_state(Clock::time_point now) override { set_ticks(0, 0, now); }

 private:
  std::array<double, 2> base_{};  // at base_time_
  std::array<double, 2> rate_{};
  Clock::time_point base_time_{};
};

// BR-SBS1: infrared beacon scanner; reports the visible beacons among the ids set.
class Sbs1 final : public Device {
 public:
  static constexpr std::uint8_t kSetBeaconIds = 0x01, kGetBeaconData = 0x02, kGetDebugData = 0x03;
  struct Sighting {
    double bearing_deg;  // counter-clockwise from the robot's heading
    std::uint8_t quality;
  };

  explicit Sbs1(std::uint8_t addr) : Device("sbs1", addr) {}
  void set_beacon(std::uint8_t id, std::optional<Sighting> s);  // nullopt = not visible
  void set_ids(std::vector<std::uint8_t> ids) { ids_ = std::move(ids); }
  // The ids in effect after power-on and RESET.
  void set_initial_ids(std::vector<std::uint8_t> ids) { initial_ids_ = ids_ = std::move(ids); }
  const std::vector<std::uint8_t>& ids() const { return ids_; }

  void set(const std::string& key, const std::vector<std::string>& args) override;
  std::string show(Clock::time_point now) const override;

 protected:
  std::optional<Result> execute(std::uint8_t instr, std::span<const std::uint8_t> data,
                                Clock::time_point now) override;
  void reset_state(Clock::time_point) override { ids_ = initial_ids_; }

 private:
  std::map<std::uint8_t, Sighting> visible_;
  std::vector<std::uint8_t> ids_;  // what SET_BEACON_IDS set
  std::vector<std::uint8_t> initial_ids_;
};

// BR-PSC1: eight power channels, currents, spontaneous PAUSE and POWER events.
class Psc1 final : public Device {
 public:
  static constexpr std::size_t kChannels = 8;
  static constexpr std::uint8_t kGetPwrStatus = 0x01, kSetPwrStatus = 0x02, kGetCurrents = 0x03,
                                kPauseEvent = 0x40, kPowerEvent = 0x41;

  explicit Psc1(std::uint8_t addr) : Device("psc1", addr) {}
  void set_boot_status(std::uint8_t mask) { boot_status_ = status_ = mask; }
  void set_status(std::uint8_t mask) { status_ = mask; }
  std::uint8_t status() const { return status_; }
  void set_current(std::size_t ch, std::optional<double> amps);  // nullopt = no sensor
  // Spontaneous frames now; periods (0 = off) for periodic ones.
  void send_pause_event(bool engaged, std::uint8_t sources);
  void send_power_event() { emit_event(kPowerEvent, {status_}); }
  void set_pause_period(std::chrono::milliseconds p, Clock::time_point now);
  void set_power_period(std::chrono::milliseconds p, Clock::time_point now);
  // PAUSE state reported by the periodic PAUSE events.
  void set_pause_state(bool engaged, std::uint8_t sources) {
    pause_engaged_ = engaged;
    pause_sources_ = sources;
  }

  void set(const std::string& key, const std::vector<std::string>& args) override;
  void poll(Clock::time_point now) override;
  std::optional<Clock::time_point> next_deadline() const override;
  std::string show(Clock::time_point now) const override;

 protected:
  std::optional<Result> execute(std::uint8_t instr, std::span<const std::uint8_t> data,
                                Clock::time_point now) override;
  // After a reset the board boots: channels as configured, then a POWER event.
  void reset_state(Clock::time_point) override {
    status_ = boot_status_;
    send_power_event();
  }

 private:
  struct Periodic {
    std::chrono::milliseconds period{0};
    Clock::time_point next{};
  };
  std::uint8_t status_ = 0, boot_status_ = 0;
  std::array<std::uint16_t, kChannels> current_ma_{};  // 0xffff = no sensor
  bool pause_engaged_ = false;
  std::uint8_t pause_sources_ = 0;
  Periodic pause_periodic_, power_periodic_;
};

// "sd1", "so1", "sbs1", "psc1"; nullptr for another type.
std::unique_ptr<Device> make_device(const std::string& type, std::uint8_t addr);

}  // namespace advee::rs485sim
