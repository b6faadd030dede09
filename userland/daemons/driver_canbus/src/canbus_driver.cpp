// SPDX-License-Identifier: GPL-2.0
#include "advee/driver_canbus/canbus_driver.hpp"

#include <chrono>
#include <future>
#include <lcm/lcm-cpp.hpp>
#include <system_error>

#include "advee/driver_canbus/messages.hpp"
#include "advee/module/time.hpp"
#include "advee/msgs/channels.hpp"
#include "lowlevel/data_drives_t.hpp"

namespace advee::driver_canbus {

using module::ExitKind;
using module::ModuleExit;
using ModuleState = module::State;  // State alone is the drives' (controller.cpp)

CanbusDriver::CanbusDriver(module::Module& m, const CanbusConfig& cfg) : m_(m), cfg_(cfg), bus_state_(cfg_.interface) {
  canopen::MasterConfig mc;
  mc.node_id = cfg_.master_node;
  mc.heartbeat_period = cfg_.master_heartbeat;
  try {
    runtime_ = std::make_unique<canopen::MasterRuntime>(loop_, cfg_.interface, mc, [this](const canopen::CanErrorInfo& e) {
      auto r = bus_state_.on_error(e);
      if (!r) return;
      m_.errors().report(r->severity, module::ErrorType::Device, kErrBus, r->text);
      for (const auto& [code, active] : r->emcy) runtime_->master().set_error(code, active);
    });
  } catch (const std::system_error& e) {
    throw ModuleExit(ExitKind::Device, kExitNoInterface,
                     "CAN interface " + cfg_.interface + ": " + e.what() +
                         " (driver_canbus.interface: can0 on the robot, vcan0 in tests)");
  }
  // ErrorReporter::report is thread-safe: the CAN loop reports directly.
  controller_ = std::make_unique<DriveController>(
      runtime_->master(), cfg_.controller,
      [this](module::Severity s, module::ErrorType t, int n, std::string text) {
        m_.errors().report(s, t, n, std::move(text));
      });

  motion_sub_.emplace(m_.lcm(), std::string(msgs::kCmdMotion.name), [this](const lowlevel::cmd_motion_t& c) {
    if (m_.state() != ModuleState::Run) return;  // PAUSE: no targets are sent
    const double v = c.speed_mps, s = c.steering_rad;
    loop_.post([this, v, s] { controller_->motion(v, s); });
  });
  homing_sub_.emplace(m_.lcm(), std::string(msgs::kCmdHoming.name), [this](const lowlevel::cmd_homing_t& c) {
    if (c.axis != lowlevel::cmd_homing_t::AXIS_STEERING) {
      m_.errors().report(module::Severity::Warning, module::ErrorType::Unknown, kErrRefused,
                         "LL_CMD_HOMING from " + c.module + ": unknown axis " + std::to_string(c.axis));
      return;
    }
    if (m_.state() != ModuleState::Run) {
      m_.errors().report(module::Severity::Warning, module::ErrorType::Unknown, kErrRefused,
                         "LL_CMD_HOMING from " + c.module + " ignored: module is in " +
                             std::string(module::to_string(m_.state())));
      return;
    }
    loop_.post([this] { controller_->home_steering(); });
  });
  // In every module state: a stop must hold even across a PAUSE.
  stop_sub_.emplace(m_.lcm(), std::string(msgs::kEventStop.name), [this](const lowlevel::event_stop_t& e) {
    const bool stop = e.stop;
    loop_.post([this, stop] { controller_->stop_event(stop); });
  });
  m_.on_state_change([this](ModuleState, ModuleState to) {
    if (to == ModuleState::Run)
      loop_.post([this] { controller_->resume(); });
    else
      loop_.post([this] { controller_->pause(); });
  });
  // LL_DATA_DRIVES in every state (the drives' state matters most when stopped).
  m_.every(
      std::chrono::nanoseconds(static_cast<std::int64_t>(1e9 / cfg_.publish_hz)),
      [this] {
        loop_.post([this] {
          DrivesStatus s = controller_->status();
          m_.post([this, s] { publish(s); });
        });
      },
      false);

  loop_.post([this] {
    controller_->start([this](bool ok, const std::string& why) {
      if (ok) return;
      m_.post([why] { throw ModuleExit(ExitKind::Device, kExitBootFailed, "cannot boot the drives: " + why); });
    });
  });
  thread_ = std::make_unique<canopen::LoopThread>(loop_, [this](std::exception_ptr failure) {
    std::string why = "unknown exception";
    try {
      std::rethrow_exception(failure);
    } catch (const std::exception& e) {
      why = e.what();
    } catch (...) {
    }
    // Module::run() reports it (fatal, number 0x23) and returns the code.
    m_.post([why, ifname = cfg_.interface] {
      throw ModuleExit(ExitKind::Device, kExitCanFailed, "CAN loop on " + ifname + " failed: " + why);
    });
  });
}

CanbusDriver::~CanbusDriver() {
  // Leave the drives quick-stopped rather than waiting for them to notice the
  // master's heartbeat is gone.
  auto stopped = std::make_shared<std::promise<void>>();
  auto f = stopped->get_future();
  loop_.post([this, stopped] {
    controller_->pause();
    stopped->set_value();
  });
  f.wait_for(std::chrono::milliseconds(200));
  thread_.reset();
}

void CanbusDriver::publish(const DrivesStatus& s) {
  auto msg = drives_message(s);
  msg.utime = module::utime_now();
  msg.module = m_.name();
  m_.lcm().publish(std::string(msgs::kDataDrives.name), &msg);
}

}  // namespace advee::driver_canbus
