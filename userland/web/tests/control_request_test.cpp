// SPDX-License-Identifier: GPL-2.0
// The WebSocket's control messages: exactly the documented ones pass, with
// their values; anything else (malformed, oversized, out of range, unknown,
// unconfirmed) is refused with a reason.
#include "advee/web/control_request.hpp"

#include <gtest/gtest.h>

#include <random>
#include <string>

#include "common/data_state_t.hpp"

namespace advee::web {
namespace {

const DriveLimits kLimits{0.5, 0.5};

ControlRequest accepted(const std::string& text) {
  const auto p = parse_control_request(text, kLimits);
  EXPECT_TRUE(p.request) << text << ": " << p.error;
  return p.request.value_or(ControlRequest{});
}

std::string refused(const std::string& text) {
  const auto p = parse_control_request(text, kLimits);
  EXPECT_FALSE(p.request) << text;
  EXPECT_FALSE(p.error.empty()) << text;
  return p.error;
}

TEST(ControlRequest, Drive) {
  const auto r = accepted(R"({"type":"drive","speed_mps":0.25,"steering_rad":-0.1})");
  EXPECT_EQ(r.kind, ControlRequest::Kind::drive);
  EXPECT_DOUBLE_EQ(r.speed_mps, 0.25);
  EXPECT_DOUBLE_EQ(r.steering_rad, -0.1);
  EXPECT_EQ(describe_request(r), "drive 0.25 m/s steering -0.100 rad");
  accepted(R"({"type":"drive","speed_mps":-0.5,"steering_rad":0.5})");  // the limits themselves
}

TEST(ControlRequest, DriveOutsideTheLimitsOrNotANumberIsRefused) {
  refused(R"({"type":"drive","speed_mps":0.51,"steering_rad":0})");
  refused(R"({"type":"drive","speed_mps":0,"steering_rad":-0.6})");
  refused(R"({"type":"drive","speed_mps":1e999,"steering_rad":0})");
  refused(R"({"type":"drive","speed_mps":"0.1","steering_rad":0})");
  refused(R"({"type":"drive","speed_mps":0.1})");
  refused(R"({"type":"drive","speed_mps":null,"steering_rad":0})");
}

TEST(ControlRequest, StateNeedsAValidTargetAKnownStateAndConfirmation) {
  const auto r = accepted(R"({"type":"state","target":"driver_aux","state":"PAUSE","confirmed":true})");
  EXPECT_EQ(r.kind, ControlRequest::Kind::state);
  EXPECT_EQ(r.target, "driver_aux");
  EXPECT_EQ(r.state, common::data_state_t::PAUSE);
  EXPECT_EQ(describe_request(r), "state driver_aux PAUSE");
  EXPECT_EQ(accepted(R"({"type":"state","target":"*","state":"STOP","confirmed":true})").state,
            common::data_state_t::STOP);
  EXPECT_EQ(refused(R"({"type":"state","target":"driver_aux","state":"RUN"})"), "state: not confirmed");
  refused(R"({"type":"state","target":"driver_aux","state":"RUN","confirmed":"yes"})");
  refused(R"({"type":"state","target":"driver aux","state":"RUN","confirmed":true})");
  refused(R"({"type":"state","target":"","state":"RUN","confirmed":true})");
  refused(R"({"type":"state","target":"x","state":"INIT","confirmed":true})");
  refused(R"({"type":"state","target":"x","state":3,"confirmed":true})");
  refused(R"({"type":"state","target":")" + std::string(33, 'a') + R"(","state":"RUN","confirmed":true})");
}

TEST(ControlRequest, Power) {
  auto r = accepted(R"({"type":"power","action":"output","output":3,"on":false,"confirmed":true})");
  EXPECT_EQ(r.power, ControlRequest::PowerAction::output);
  EXPECT_EQ(r.output, 3);
  EXPECT_FALSE(r.on);
  EXPECT_EQ(accepted(R"({"type":"power","action":"reboot","confirmed":true})").power,
            ControlRequest::PowerAction::reboot);
  EXPECT_EQ(accepted(R"({"type":"power","action":"poweroff","confirmed":true})").power,
            ControlRequest::PowerAction::poweroff);
  refused(R"({"type":"power","action":"poweroff"})");
  refused(R"({"type":"power","action":"output","output":16,"on":true,"confirmed":true})");
  refused(R"({"type":"power","action":"output","output":-1,"on":true,"confirmed":true})");
  refused(R"({"type":"power","action":"output","output":1.5,"on":true,"confirmed":true})");
  refused(R"({"type":"power","action":"output","output":1,"confirmed":true})");
  refused(R"({"type":"power","action":"explode","confirmed":true})");
}

TEST(ControlRequest, TakeReleaseStopHoming) {
  EXPECT_FALSE(accepted(R"({"type":"take"})").force);
  EXPECT_TRUE(accepted(R"({"type":"take","force":true})").force);
  refused(R"({"type":"take","force":1})");
  EXPECT_EQ(accepted(R"({"type":"release"})").kind, ControlRequest::Kind::release);
  EXPECT_EQ(accepted(R"({"type":"stop"})").kind, ControlRequest::Kind::stop);
  // Only the bridge names a cause: a page's stop is an operator's.
  EXPECT_EQ(describe_request(accepted(R"({"type":"stop"})")), "stop");
  EXPECT_EQ(accepted(R"({"type":"homing","axis":"steering"})").kind, ControlRequest::Kind::homing);
  refused(R"({"type":"homing","axis":"propulsion"})");
}

TEST(ControlRequest, MalformedIsRefused) {
  for (const char* s : {"", "{", "null", "[]", "\"drive\"", "42", "{}", R"({"type":1})", R"({"type":"fly"})",
                        "{\"type\":\"stop\"", "\xff\xfe", R"({"type":"stop"} trailing)"})
    refused(s);
}

TEST(ControlRequest, OversizedIsRefusedUnread) {
  std::string big = R"({"type":"stop","pad":")" + std::string(kMaxControlMessageBytes, 'x') + "\"}";
  EXPECT_EQ(refused(big), "message too long");
  std::string nested(kMaxControlMessageBytes + 1, '[');
  refused(nested);
}

// Random bytes and mutated valid messages: never an exception, never a crash;
// whatever passes is within the limits.
TEST(ControlRequest, FuzzNeverThrowsAndKeepsLimits) {
  std::mt19937 rng(22);
  const std::string seeds[] = {R"({"type":"drive","speed_mps":0.25,"steering_rad":-0.1})",
                               R"({"type":"state","target":"driver_aux","state":"RUN","confirmed":true})",
                               R"({"type":"power","action":"output","output":3,"on":true,"confirmed":true})"};
  for (int i = 0; i < 20000; ++i) {
    std::string s = seeds[i % 3];
    if (i % 4 == 0) {
      s.assign(rng() % 200, '\0');
      for (auto& c : s) c = static_cast<char>(rng());
    } else {
      for (int k = rng() % 4; k >= 0; --k) s[rng() % s.size()] = static_cast<char>(rng());
    }
    ParsedControl p;
    ASSERT_NO_THROW(p = parse_control_request(s, kLimits));
    if (p.request && p.request->kind == ControlRequest::Kind::drive) {
      EXPECT_LE(std::abs(p.request->speed_mps), kLimits.max_speed_mps);
      EXPECT_LE(std::abs(p.request->steering_rad), kLimits.max_steering_rad);
    }
  }
}

}  // namespace
}  // namespace advee::web
