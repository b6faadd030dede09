// SPDX-License-Identifier: GPL-2.0
#include <gtest/gtest.h>
#include <unistd.h>

#include <algorithm>
#include <filesystem>
#include <fstream>

#include "advee/robotsim/sinks.hpp"
#include "test_util.hpp"

namespace advee::robotsim {
namespace {

struct Recorder {
  std::vector<std::string> sent;
  Rs485SimSink::Send send() {
    return [this](const std::string& c) { sent.push_back(c); };
  }
  bool has(const std::string& c) const { return std::find(sent.begin(), sent.end(), c) != sent.end(); }
};

TEST(Rs485SimSink, SendsEveryValueOnceThenOnlyChanges) {
  Robot r(test::exact_robot(), test::example_room());
  Recorder rec;
  Rs485SimSink sink(Rs485Devices{}, r.description(), rec.send());
  SensorFrame f = r.sense();
  sink.publish(f);
  // From (2.3, 2) the box hides beacon 3: 16 SRF + 4 IR + ticks + 3 beacons.
  ASSERT_EQ(f.beacons.size(), 3u);
  ASSERT_EQ(f.beacons[0].id, 1);
  EXPECT_EQ(rec.sent.size(), 16u + 4u + 1u + 3u);
  EXPECT_TRUE(rec.has("set b:sbs1@0x30 beacon 4 " + [&] {
    char b[32];
    std::snprintf(b, sizeof b, "%.2f", f.beacons[2].bearing_cdeg / 100.0);
    return std::string(b);
  }() + " " + std::to_string(f.beacons[2].quality)));
  EXPECT_TRUE(rec.has("set a:so1@0x20 ticks 0 0"));
  EXPECT_TRUE(rec.has("set a:sd1@0x11 ir 1 0.120"));
  EXPECT_TRUE(rec.has("set b:sbs1@0x30 beacon 1 " + [&] {
    char b[32];
    std::snprintf(b, sizeof b, "%.2f", f.beacons[0].bearing_cdeg / 100.0);
    return std::string(b);
  }() + " " + std::to_string(f.beacons[0].quality)));
  rec.sent.clear();
  sink.publish(f);
  EXPECT_TRUE(rec.sent.empty());
  f.srf_m[3] = std::nullopt;
  f.ticks = {100, 101};
  f.beacons.erase(f.beacons.begin());  // beacon 1 lost from sight
  sink.publish(f);
  EXPECT_EQ(rec.sent, (std::vector<std::string>{"set a:sd1@0x10 srf 3 none", "set a:so1@0x20 ticks 100 101",
                                                  "set b:sbs1@0x30 beacon 1 none"}));
}

TEST(Rs485SimSink, RaisesPauseSourcesOnTheirRisingEdge) {
  Robot r(test::exact_robot(), test::example_room());
  Recorder rec;
  Rs485SimSink sink(Rs485Devices{}, r.description(), rec.send());
  SensorFrame f = r.sense();
  sink.publish(f);
  rec.sent.clear();
  f.pause = kPauseFrontBumper;
  sink.publish(f);
  sink.publish(f);  // still touching: no second raise
  f.pause = kPauseFrontBumper | kPauseRearBumper;
  sink.publish(f);
  f.pause = 0;
  sink.publish(f);
  // The SD1s latch their sources; the PSC1 reports the PAUSE line's every change.
  EXPECT_EQ(rec.sent, (std::vector<std::string>{"set a:sd1@0x10 pause 1", "event power:psc1@0x01 pause 1 1",
                                                  "set a:sd1@0x11 pause 2", "event power:psc1@0x01 pause 1 3",
                                                  "event power:psc1@0x01 pause 0 0"}));
}

TEST(Rs485SimSink, NoPsc1NoPauseEvents) {
  Robot r(test::exact_robot(), test::example_room());
  Recorder rec;
  Rs485Devices dev;
  dev.psc1.clear();
  Rs485SimSink sink(dev, r.description(), rec.send());
  SensorFrame f = r.sense();
  sink.publish(f);
  rec.sent.clear();
  f.pause = kPauseFrontBumper;
  sink.publish(f);
  EXPECT_EQ(rec.sent, (std::vector<std::string>{"set a:sd1@0x10 pause 1"}));
}

TEST(Max6615DebugfsSink, WritesMillidegrees) {
  char tmpl[] = "/tmp/robotsim-max6615-XXXXXX";
  ASSERT_NE(mkdtemp(tmpl), nullptr);
  const std::string dir = tmpl;
  Max6615DebugfsSink sink(dir);
  SensorFrame f;
  f.temperature_c = {31.4567, 25.0};
  sink.publish(f);
  const auto read = [&](const char* name) {
    std::ifstream in(dir + "/" + name);
    long v = -1;
    in >> v;
    return v;
  };
  EXPECT_EQ(read("temp1"), 31457);
  EXPECT_EQ(read("temp2"), 25000);
  std::filesystem::remove_all(dir);
  EXPECT_THROW(sink.publish(f), std::system_error);  // directory gone: reported
}

}  // namespace
}  // namespace advee::robotsim
