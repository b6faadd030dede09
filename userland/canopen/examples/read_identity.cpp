// SPDX-License-Identifier: GPL-2.0
// read-identity IFACE NODE: the identity object 0x1018 (vendor, product,
// revision, serial number) of one CANopen node, read by SDO over SocketCAN.
// The example of docs/canopen.md ("Libraries"): it uses only the installed
// libraries (advee_canopen_socketcan and the engine below it).
#include <array>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <exception>

#include "advee/canopen/event_loop.hpp"
#include "advee/canopen/runtime.hpp"

using namespace advee::canopen;

int main(int argc, char** argv) {
  if (argc != 3) {
    std::fprintf(stderr, "usage: read-identity IFACE NODE (e.g. read-identity can0 1)\n");
    return 2;
  }
  const unsigned long node = std::strtoul(argv[2], nullptr, 0);
  if (node < 1 || node > 127) {
    std::fprintf(stderr, "read-identity: NODE is 1..127\n");
    return 2;
  }
  static constexpr std::array<const char*, 4> kNames{"vendor", "product", "revision", "serial"};
  int rc = 0;
  try {
    EventLoop loop;                                   // epoll + timerfd
    MasterRuntime rt(loop, argv[1], MasterConfig{});  // CAN_RAW socket -> passive Master
    SdoClient& sdo = rt.master().sdo(static_cast<std::uint8_t>(node));
    // One transfer per node at a time: the client queues the other three.
    for (std::uint8_t sub = 1; sub <= 4; ++sub) {
      sdo.read<std::uint32_t>(0x1018, sub, [&, sub](std::error_code ec, std::uint32_t v) {
        if (ec) {
          std::fprintf(stderr, "read-identity: 0x1018:%u: %s\n", sub, ec.message().c_str());
          rc = 1;
        } else {
          std::printf("%-8s 0x%08X\n", kNames[sub - 1], static_cast<unsigned>(v));
        }
        if (sub == 4) loop.stop();
      });
    }
    loop.run();
  } catch (const std::exception& e) {  // no such interface, no permission
    std::fprintf(stderr, "read-identity: %s\n", e.what());
    return 1;
  }
  return rc;
}
