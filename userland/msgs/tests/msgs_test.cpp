// SPDX-License-Identifier: GPL-2.0
// The generated types survive encode/decode with every field, the LCM type
// check rejects a message of another type, and channel names follow the
// thesis convention.
#include <gtest/gtest.h>

#include <cctype>
#include <set>
#include <string>
#include <vector>

#include "advee/msgs/channels.hpp"
#include "advee/msgs/describe.hpp"
#include "lowlevel/data_drives_t.hpp"
#include "common/cmd_state_t.hpp"
#include "common/data_state_t.hpp"
#include "common/error_t.hpp"
#include "lowlevel/data_fans_t.hpp"
#include "lowlevel/data_srfs_t.hpp"
#include "lowlevel/data_temperature_t.hpp"

namespace {

template <typename T>
std::vector<unsigned char> encode(const T& m) {
  std::vector<unsigned char> buf(m.getEncodedSize());
  EXPECT_EQ(m.encode(buf.data(), 0, static_cast<int>(buf.size())), static_cast<int>(buf.size()));
  return buf;
}

template <typename T>
T decode(const std::vector<unsigned char>& buf) {
  T m;
  EXPECT_EQ(m.decode(buf.data(), 0, static_cast<int>(buf.size())), static_cast<int>(buf.size()));
  return m;
}

TEST(Msgs, ErrorRoundTrip) {
  common::error_t e;
  e.utime = 1'700'000'000'123'456;
  e.module = "driver_aux";
  e.number = 19;
  e.text = "no hwmon device named max6615";
  e.fatal = true;
  e.type = common::error_t::TYPE_DEVICE;
  e.severity = common::error_t::SEVERITY_ERROR;
  e.file = "driver_aux.cpp";
  e.line = 42;
  auto d = decode<common::error_t>(encode(e));
  EXPECT_EQ(d.utime, e.utime);
  EXPECT_EQ(d.module, e.module);
  EXPECT_EQ(d.number, 19);
  EXPECT_EQ(d.text, e.text);
  EXPECT_TRUE(d.fatal);
  EXPECT_EQ(d.type, common::error_t::TYPE_DEVICE);
  EXPECT_EQ(d.severity, common::error_t::SEVERITY_ERROR);
  EXPECT_EQ(d.file, e.file);
  EXPECT_EQ(d.line, 42);
}

TEST(Msgs, VariableArraysRoundTrip) {
  lowlevel::data_srfs_t s;
  s.utime = 5;
  s.module = "driver_rs485";
  s.num_srfs = 3;
  s.srf_id = {1, 2, 7};
  s.srf_range_m = {0.25f, 1.5f, -1.0f};
  s.num_irs = 1;
  s.ir_id = {9};
  s.ir_range_m = {0.8f};
  auto d = decode<lowlevel::data_srfs_t>(encode(s));
  EXPECT_EQ(d.srf_id, s.srf_id);
  EXPECT_EQ(d.srf_range_m, s.srf_range_m);
  EXPECT_EQ(d.ir_id, s.ir_id);
  EXPECT_EQ(d.ir_range_m, s.ir_range_m);

  lowlevel::data_temperature_t t;
  t.utime = 6;
  t.module = "driver_aux";
  t.count = 2;
  t.label = {"temp1", "temp2"};
  t.celsius = {39.625f, 45.125f};
  auto dt = decode<lowlevel::data_temperature_t>(encode(t));
  EXPECT_EQ(dt.label, t.label);
  EXPECT_EQ(dt.celsius, t.celsius);

  lowlevel::data_fans_t f;
  f.utime = 7;
  f.module = "driver_aux";
  f.count = 2;
  f.label = {"fan1", "fan2"};
  f.rpm = {975, -1};
  f.fault = {false, true};
  f.fan_fail = true;
  f.pwm = {51, -1};
  auto df = decode<lowlevel::data_fans_t>(encode(f));
  EXPECT_EQ(df.rpm, f.rpm);
  EXPECT_EQ(df.fault, f.fault);
  EXPECT_TRUE(df.fan_fail);
  EXPECT_EQ(df.pwm, f.pwm);
}

TEST(Msgs, TypeMismatchIsRejected) {
  common::data_state_t s;
  s.utime = 1;
  s.module = "x";
  s.state = common::data_state_t::RUN;
  s.pid = 12;
  auto buf = encode(s);
  common::cmd_state_t c;
  EXPECT_LT(c.decode(buf.data(), 0, static_cast<int>(buf.size())), 0);
}

TEST(Msgs, TruncatedMessageIsRejected) {
  common::cmd_state_t c;
  c.utime = 1;
  c.module = "diag";
  c.target = "driver_aux";
  c.state = common::data_state_t::PAUSE;
  c.manual = false;
  auto buf = encode(c);
  buf.resize(buf.size() - 3);
  common::cmd_state_t d;
  EXPECT_LT(d.decode(buf.data(), 0, static_cast<int>(buf.size())), 0);
}

TEST(Msgs, ChannelNamesFollowTheConvention) {
  std::set<std::string_view> names;
  for (const auto& ch : advee::msgs::kAllChannels) {
    EXPECT_TRUE(names.insert(ch.name).second) << ch.name << " listed twice";
    std::string n(ch.name);
    const auto p1 = n.find('_');
    ASSERT_NE(p1, std::string::npos) << n;
    const auto prefix = n.substr(0, p1);
    EXPECT_TRUE(prefix == "LL" || prefix == "CM") << n;
    const auto p2 = n.find('_', p1 + 1);
    ASSERT_NE(p2, std::string::npos) << n;
    const auto kind = n.substr(p1 + 1, p2 - p1 - 1);
    EXPECT_TRUE(kind == "CMD" || kind == "DATA" || kind == "EVENT") << n;
    for (char c : n) EXPECT_TRUE(std::isupper(static_cast<unsigned char>(c)) || c == '_') << n;
    // Commands and events are aperiodic; periodic data has a rate.
    if (kind != "DATA") {
      EXPECT_EQ(ch.rate_hz, 0) << n;
    }
    // The type's package matches the prefix (LL -> lowlevel, CM -> common).
    EXPECT_EQ(ch.type.substr(0, ch.type.find('.')), prefix == "LL" ? "lowlevel" : "common") << n;
  }
}

}  // namespace

// The listeners' text lines (advee/msgs/describe.hpp): what the VM tests grep.
namespace {

lcm::ReceiveBuffer buffer_of(std::vector<std::uint8_t>& bytes) {
  lcm::ReceiveBuffer rb{};
  rb.data = bytes.data();
  rb.data_size = static_cast<std::uint32_t>(bytes.size());
  return rb;
}

template <typename Msg>
std::vector<std::uint8_t> encoded(const Msg& m) {
  std::vector<std::uint8_t> b(static_cast<std::size_t>(m.getEncodedSize()));
  m.encode(b.data(), 0, static_cast<int>(b.size()));
  return b;
}

TEST(Describe, DrivesLineHasEveryKeyTheTestsRead) {
  lowlevel::data_drives_t d{};
  d.module = "driver_canbus";
  d.num_drives = 2;
  d.axis = {0, 1};
  d.node = {1, 2};
  d.state = {"operation enabled", "fault"};
  d.fault = {false, true};
  d.error_code = {0, 0x4210};
  d.homed = {false, true};
  d.speed_mps = 0.5;
  d.steering_rad = 0.2;
  d.stopped = true;
  d.stop_reason = "command timeout";
  auto bytes = encoded(d);
  const auto line = advee::msgs::describe(buffer_of(bytes), "LL_DATA_DRIVES");
  EXPECT_EQ(line.rfind("LL_DATA_DRIVES t=", 0), 0u) << line;
  for (const char* kv : {" module=driver_canbus ", " speed=0.5000 ", " steering=0.2000 ", " stopped=1 ",
                         " reason=command_timeout ", " node1=operation_enabled ", " fault2=1 ", " emcy2=16912 ",
                         " homed2=1"})
    EXPECT_NE(line.find(kv), std::string::npos) << kv << " in " << line;
}

TEST(Describe, ABrokenOrUnknownMessageSaysUndecoded) {
  std::vector<std::uint8_t> junk{1, 2, 3};
  const auto rb = buffer_of(junk);
  EXPECT_NE(advee::msgs::describe(rb, "LL_DATA_ODO").find(" undecoded bytes=3"), std::string::npos);
  EXPECT_NE(advee::msgs::describe(rb, "SOMETHING_ELSE").find(" undecoded bytes=3"), std::string::npos);
}

}  // namespace
