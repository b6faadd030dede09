// SPDX-License-Identifier: GPL-2.0
// The configuration file: a full example loads; mistakes name line and field.
#include <gtest/gtest.h>

#include "advee/rs485sim/config.hpp"
#include "advee/rs485sim/devices.hpp"
#include "test_util.hpp"

namespace advee::rs485sim {
namespace {

using test::bytes;

constexpr const char* kExample = R"(control: /run/rs485-sim.sock
seed: 42
buses:
  - name: a
    wire: /dev/ts7800-sim/uart0
    devices:
      - type: sd1
        address: 0x10
        firmware: [1, 4]
        response_us: [200, 2000]
        srf_m: [0.5, 1.0, null, 2.0]
        ir_m: [0.1, none]
        faults: {bad_crc: 0.01, no_answer: once:2, slow_ms: 300}
      - type: so1
        address: 0x20
        ticks: [10, -10]
  - name: b
    wire: /dev/ts7800-sim/uart1
    devices:
      - type: sbs1
        address: 0x30
        ids: [1, 2]
        beacons:
          - {id: 1, bearing_deg: 12.5, quality: 180}
  - name: power
    wire: /dev/ts7800-sim/uart2
    duplex: full
    devices:
      - {type: psc1, address: 0x01, status: 0x0f, currents_a: [0.25, null], power_period_ms: 1000}
)";

std::string error_of(const std::string& yaml) {
  try {
    load_config_string(yaml, "sim.yaml");
  } catch (const ConfigError& e) {
    return e.what();
  }
  return "(no error)";
}

TEST(Config, FullExampleLoads) {
  auto cfg = load_config_string(kExample);
  EXPECT_EQ(cfg.control, "/run/rs485-sim.sock");
  EXPECT_EQ(cfg.seed, 42u);
  ASSERT_EQ(cfg.buses.size(), 3u);
  EXPECT_EQ(cfg.buses[0].wire, "/dev/ts7800-sim/uart0");
  EXPECT_EQ(cfg.buses[0].bus->devices().size(), 2u);
  EXPECT_TRUE(cfg.buses[2].bus->full_duplex());
  auto* sd1 = cfg.buses[0].bus->find(0x10);
  ASSERT_NE(sd1, nullptr);
  EXPECT_EQ(sd1->faults().no_answer.once, 2u);
  EXPECT_DOUBLE_EQ(sd1->faults().bad_crc.probability, 0.01);
  EXPECT_EQ(sd1->faults().slow_delay, std::chrono::milliseconds(300));
  sd1->faults() = Faults{};
  const auto r = test::transact(*cfg.buses[0].bus, Frame{0x10, Sd1::kGetBoth, 0, {}});
  ASSERT_EQ(r.size(), 1u);
  EXPECT_EQ(r[0].frame.data,
            bytes({8, 50, 0, 100, 0, 0xff, 0xff, 200, 0, 0, 0, 0, 0, 0, 0, 0, 0, 2, 50, 0}));
  const auto fw = test::transact(*cfg.buses[0].bus, Frame{0x10, kInstrGetFwVersion, 0, {}});
  EXPECT_EQ(fw.at(0).frame.data, bytes({1, 4}));
  const auto b = test::transact(*cfg.buses[1].bus, Frame{0x30, Sbs1::kGetBeaconData, 0, {}});
  EXPECT_EQ(b.at(0).frame.data, bytes({1, 1, 0xe2, 0x04, 180}));
}

TEST(Config, UnknownKeyNamesLineAndField) {
  const auto e = error_of("buses:\n  - name: a\n    wire: /dev/x\n    devices:\n      - type: sd1\n"
                          "        address: 0x10\n        srf: [1]\n");
  EXPECT_EQ(e.rfind("sim.yaml:7:", 0), 0u) << e;
  EXPECT_NE(e.find("buses[0].devices[0].srf: unknown key"), std::string::npos) << e;
}

TEST(Config, BadValuesAreReportedWithTheirField) {
  EXPECT_NE(error_of("buses:\n  - {name: a, wire: /x, devices: [{type: so1, address: 0x100}]}\n")
                .find("buses[0].devices[0].address"), std::string::npos);
  EXPECT_NE(error_of("buses:\n  - {name: a, wire: /x, devices: [{type: xx1, address: 1}]}\n")
                .find("unknown device type 'xx1'"), std::string::npos);
  EXPECT_NE(error_of("buses:\n  - {name: a, wire: /x, devices: [{type: sd1, address: 1}, {type: so1, address: 1}]}\n")
                .find("address already taken"), std::string::npos);
  EXPECT_NE(error_of("buses:\n  - {name: a, devices: []}\n").find("buses[0].wire: missing"), std::string::npos);
  EXPECT_NE(error_of("buses:\n  - {name: a, wire: /x, devices: [{type: sd1, address: 1, faults: {bad_crc: 2}}]}\n")
                .find("not in 0..1"), std::string::npos);
  EXPECT_NE(error_of("buses:\n  - {name: a, wire: /x, devices: [{type: psc1, address: 1, pause_period_ms: 5}]}\n")
                .find("full-duplex"), std::string::npos);
  EXPECT_NE(error_of("buses: [\n").find("YAML syntax"), std::string::npos);
  EXPECT_NE(error_of("{}\n").find("buses: missing"), std::string::npos);
}

}  // namespace
}  // namespace advee::rs485sim
