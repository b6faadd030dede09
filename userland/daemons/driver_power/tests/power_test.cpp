// SPDX-License-Identifier: GPL-2.0
// driver_power on FakeTransport and LCM memq://: status and currents on
// LL_DATA_POWER, LL_CMD_POWER -> SET_PWR_STATUS, PAUSE events ->
// LL_EVENT_STOP, POWER events -> LL_DATA_POWER, the power-off/reboot
// commands (a marker file, never the real one), bad commands, configuration.
#include <gtest/gtest.h>

#include <filesystem>
#include <lcm/lcm-cpp.hpp>
#include <memory>

#include "advee/module/subscription.hpp"
#include "advee/module/manual_loop.hpp"
#include <mutex>

#include "advee/driver_power/power_driver.hpp"
#include "advee/rs485/fake_transport.hpp"
#include "common/error_t.hpp"
#include "lowlevel/cmd_power_t.hpp"
#include "lowlevel/data_power_t.hpp"
#include "lowlevel/event_stop_t.hpp"

using namespace advee;
using namespace advee::driver_power;
using namespace std::chrono_literals;
using rs485::FakeTransport;
namespace fs = std::filesystem;

namespace {

// The modules run on a manual clock: `d` of module time in 1 ms steps, each
// followed by the loop passes that handle what became ready (memq delivers
// on the pass after a publish). No wall-clock wait: the transport, the
// events and the commands are synchronous.
module::ManualTimers clock_;
void spin(module::Module& m, std::chrono::milliseconds d) { module::run_manual(m, clock_, d); }

struct Rx {
  std::vector<lowlevel::data_power_t> power;
  std::vector<lowlevel::event_stop_t> stops;
  std::vector<common::error_t> errors;
  // module::Subscription: LCM's member-function subscriptions trip UBSan.
  std::vector<std::shared_ptr<void>> subs;
  void subscribe(lcm::LCM& l) {
    subs.push_back(std::make_shared<module::Subscription<lowlevel::data_power_t>>(l, "LL_DATA_POWER", [this](const lowlevel::data_power_t& m) { power.push_back(m); }));
    subs.push_back(std::make_shared<module::Subscription<lowlevel::event_stop_t>>(l, "LL_EVENT_STOP", [this](const lowlevel::event_stop_t& m) { stops.push_back(m); }));
    subs.push_back(std::make_shared<module::Subscription<common::error_t>>(l, "CM_DATA_ERROR", [this](const common::error_t& m) { errors.push_back(m); }));
  }
  int errors_numbered(int n) const {
    int c = 0;
    for (const auto& x : errors) c += x.number == n;
    return c;
  }
};

// A PSC1 at 0x01: status register, currents 0.5 A per powered channel
// with a sensor (channels 6, 7 have none).
struct Psc1Model {
  std::mutex mu;
  std::uint8_t status = 0x0f;
  std::vector<std::vector<std::uint8_t>> sets;
  rs485::Result respond(const rs485::Request& r) {
    std::lock_guard l(mu);
    using namespace rs485::psc1::instr;
    switch (r.instr) {
      case kGetPowerStatus: return FakeTransport::ack({status});
      case kSetPowerStatus:
        sets.push_back(r.data);
        status = static_cast<std::uint8_t>((status & ~r.data[0]) | (r.data[0] & r.data[1]));
        return FakeTransport::ack({status});
      case kGetCurrents: {
        std::vector<std::uint8_t> d;
        for (unsigned ch = 0; ch < 8; ++ch) {
          const unsigned ma = ch >= 6 ? 0xffff : (status >> ch & 1) ? 500 + ch : 0;
          d.push_back(static_cast<std::uint8_t>(ma & 0xff));
          d.push_back(static_cast<std::uint8_t>(ma >> 8));
        }
        return FakeTransport::ack(d);
      }
    }
    return FakeTransport::fail(rs485::Outcome::unknown_instruction);
  }
};

class PowerTest : public testing::Test {
 protected:
  void SetUp() override {
    marker_ = fs::temp_directory_path() /
              ("advee-power-" + std::to_string(::getpid()) + "-" +
               testing::UnitTest::GetInstance()->current_test_info()->name());
    fs::remove(marker_);
  }
  void TearDown() override { fs::remove(marker_); }
  PowerConfig config() {
    return parse_power_config(module::ConfigNode::parse(
        "module: {lcm_url: 'memq://', print_severity: none, send_severity: notice}\n"
        "driver_power:\n  rate_hz: 20\n"
        "  poweroff_command: [touch, " + marker_.string() + ".off]\n"
        "  reboot_command: [sh, -c, 'touch " + marker_.string() + ".reboot; exit 3']\n"));
  }
  void send(module::Module& m, std::int8_t action, std::int8_t output = 0, bool on = false) {
    lowlevel::cmd_power_t c{};
    c.module = "planner";
    c.action = action;
    c.output = output;
    c.on = on;
    m.lcm().publish("LL_CMD_POWER", &c);
  }
  fs::path marker_;
};

rs485::Frame event(std::uint8_t instr, std::vector<std::uint8_t> data) {
  rs485::Frame f;
  f.addr = 0x01;
  f.instr = instr;
  f.flags = rs485::response_flag::kEvent;
  f.data = std::move(data);
  return f;
}

}  // namespace

TEST(PowerMessage, StatusBitsAndCurrents) {
  rs485::Psc1Currents c{};
  c[0] = 1.25;
  c[3] = 0.0;
  const auto m = power_message(0x09, c, true);
  EXPECT_EQ(m.num_outputs, 8);
  EXPECT_EQ(m.on, (std::vector<std::int8_t>{1, 0, 0, 1, 0, 0, 0, 0}));
  EXPECT_EQ(m.current_a, (std::vector<float>{1.25f, -1, -1, 0, -1, -1, -1, -1}));
  EXPECT_TRUE(m.paused);
  EXPECT_LT(m.battery_v, 0);  // the PSC1 does not measure it
  EXPECT_EQ(power_message(0xff, std::nullopt, false).current_a, std::vector<float>(8, -1.0f));
}

TEST(PowerConfig, ExampleAndMistakes) {
  const auto c = parse_power_config(module::ConfigNode::load_file(ADVEE_DRIVER_POWER_CONF "/driver_power.yaml"));
  EXPECT_EQ(c.module.name, "driver_power");
  EXPECT_EQ(c.bus.device, "power");
  EXPECT_EQ(c.address, 0x01);
  EXPECT_EQ(c.poweroff_command, (std::vector<std::string>{"systemctl", "poweroff"}));
  EXPECT_EQ(c.reboot_command, (std::vector<std::string>{"systemctl", "reboot"}));
  for (const char* bad : {"driver_power: {address: 255}", "driver_power: {rate_hz: 100}",
                          "driver_power: {poweroff_command: systemctl}", "driver_power: {poweroff_command: []}",
                          "driver_power: {bus: {device: a, retries: 17}}", "driver_power: {reboot: [x]}"}) {
    EXPECT_THROW(parse_power_config(module::ConfigNode::parse(bad)), module::ConfigError) << bad;
  }
}

TEST(PowerConfig, RunCommandReportsFailures) {
  EXPECT_EQ(run_command({"true"}), "");
  EXPECT_EQ(run_command({"false"}), "false exited with 1");
  EXPECT_NE(run_command({"/nonexistent/advee-poweroff"}).find("No such file"), std::string::npos);
}

TEST_F(PowerTest, PublishesStatusAndCurrents) {
  Psc1Model psc;
  FakeTransport t([&](const rs485::Request& r) { return psc.respond(r); });
  auto cfg = config();
  module::Module m(cfg.module, clock_);
  Rx rx;
  rx.subscribe(m.lcm());
  PowerDriver d(m, cfg, t);
  m.request_state(module::State::Run, false, "test");
  spin(m, 200ms);
  ASSERT_GE(rx.power.size(), 2u);
  const auto& p = rx.power.back();
  EXPECT_EQ(p.module, "driver_power");
  EXPECT_EQ(p.on, (std::vector<std::int8_t>{1, 1, 1, 1, 0, 0, 0, 0}));
  EXPECT_EQ(p.current_a, (std::vector<float>{0.5f, 0.501f, 0.502f, 0.503f, 0, 0, -1, -1}));
  EXPECT_FALSE(p.paused);
}

TEST_F(PowerTest, CommandSwitchesAnOutput) {
  Psc1Model psc;
  FakeTransport t([&](const rs485::Request& r) { return psc.respond(r); });
  auto cfg = config();
  module::Module m(cfg.module, clock_);
  Rx rx;
  rx.subscribe(m.lcm());
  PowerDriver d(m, cfg, t);
  m.request_state(module::State::Run, false, "test");
  spin(m, 30ms);
  send(m, lowlevel::cmd_power_t::ACTION_SET_OUTPUT, 5, true);
  send(m, lowlevel::cmd_power_t::ACTION_SET_OUTPUT, 1, false);
  spin(m, 80ms);
  {
    std::lock_guard l(psc.mu);
    ASSERT_EQ(psc.sets.size(), 2u);
    EXPECT_EQ(psc.sets[0], (std::vector<std::uint8_t>{0x20, 0x20}));
    EXPECT_EQ(psc.sets[1], (std::vector<std::uint8_t>{0x02, 0x00}));
    EXPECT_EQ(psc.status, 0x2d);
  }
  EXPECT_EQ(rx.power.back().on, (std::vector<std::int8_t>{1, 0, 1, 1, 0, 1, 0, 0}));
  // Out of range and unknown actions: reported, nothing sent.
  send(m, lowlevel::cmd_power_t::ACTION_SET_OUTPUT, 8, true);
  send(m, 7);
  spin(m, 30ms);
  EXPECT_EQ(rx.errors_numbered(kErrBadCommand), 2);
  std::lock_guard l(psc.mu);
  EXPECT_EQ(psc.sets.size(), 2u);
}

TEST_F(PowerTest, PauseEventBecomesAStopEventAtOnce) {
  Psc1Model psc;
  FakeTransport t([&](const rs485::Request& r) { return psc.respond(r); });
  auto cfg = config();
  module::Module m(cfg.module, clock_);
  Rx rx;
  rx.subscribe(m.lcm());
  PowerDriver d(m, cfg, t);
  // Also in PAUSE (the module's own): the stop button is never ignored.
  m.request_state(module::State::Pause, false, "test");
  t.inject_event(event(rs485::psc1::instr::kPauseEvent, {1, 0x01}));
  spin(m, 20ms);
  ASSERT_EQ(rx.stops.size(), 1u);
  EXPECT_TRUE(rx.stops[0].stop);
  EXPECT_EQ(rx.stops[0].source, lowlevel::event_stop_t::SOURCE_PSC1);
  EXPECT_EQ(rx.stops[0].module, "driver_power");
  t.inject_event(event(rs485::psc1::instr::kPauseEvent, {0, 0}));
  // A malformed event (engaged = 2) and another node's event are not stops.
  t.inject_event(event(rs485::psc1::instr::kPauseEvent, {2, 0}));
  auto other = event(rs485::psc1::instr::kPauseEvent, {1, 0});
  other.addr = 0x02;
  t.inject_event(other);
  spin(m, 20ms);
  ASSERT_EQ(rx.stops.size(), 2u);
  EXPECT_FALSE(rx.stops[1].stop);

  m.request_state(module::State::Run, false, "test");
  t.inject_event(event(rs485::psc1::instr::kPauseEvent, {1, 0x04}));
  spin(m, 120ms);
  ASSERT_FALSE(rx.power.empty());
  EXPECT_TRUE(rx.power.back().paused);
}

TEST_F(PowerTest, PowerEventPublishesTheNewStatus) {
  Psc1Model psc;
  FakeTransport t([&](const rs485::Request& r) { return psc.respond(r); });
  auto cfg = config();
  module::Module m(cfg.module, clock_);
  Rx rx;
  rx.subscribe(m.lcm());
  PowerDriver d(m, cfg, t);
  m.request_state(module::State::Pause, false, "test");  // no polling: only the event publishes
  t.inject_event(event(rs485::psc1::instr::kPowerEvent, {0x81}));
  spin(m, 30ms);
  ASSERT_EQ(rx.power.size(), 1u);
  EXPECT_EQ(rx.power[0].on, (std::vector<std::int8_t>{1, 0, 0, 0, 0, 0, 0, 1}));
}

TEST_F(PowerTest, PowerOffAndRebootRunTheConfiguredCommands) {
  Psc1Model psc;
  FakeTransport t([&](const rs485::Request& r) { return psc.respond(r); });
  auto cfg = config();
  module::Module m(cfg.module, clock_);
  Rx rx;
  rx.subscribe(m.lcm());
  PowerDriver d(m, cfg, t);
  m.request_state(module::State::Run, false, "test");
  send(m, lowlevel::cmd_power_t::ACTION_POWEROFF);
  spin(m, 100ms);
  EXPECT_TRUE(fs::exists(marker_.string() + ".off"));
  EXPECT_EQ(rx.errors_numbered(kErrCommandFailed), 0);
  send(m, lowlevel::cmd_power_t::ACTION_REBOOT);
  spin(m, 100ms);
  EXPECT_TRUE(fs::exists(marker_.string() + ".reboot"));
  EXPECT_EQ(rx.errors_numbered(kErrCommandFailed), 1);  // the reboot command exits 3
  fs::remove(marker_.string() + ".off");
  fs::remove(marker_.string() + ".reboot");
  // Not in PAUSE.
  m.request_state(module::State::Pause, false, "test");
  send(m, lowlevel::cmd_power_t::ACTION_POWEROFF);
  spin(m, 50ms);
  EXPECT_FALSE(fs::exists(marker_.string() + ".off"));
}
