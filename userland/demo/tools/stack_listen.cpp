// SPDX-License-Identifier: GPL-2.0
// advee-stack-listen: the whole-stack tests' LCM subscriber. Listens for a
// while to every channel of advee/msgs/channels.hpp (and the simulator's
// SIM_DATA_POSE) and prints one decoded line per message:
//   CHANNEL t=MONOTONIC_S module=SENDER key=value ...
// so that a shell test can count messages per channel and compare values.
// --stamps adds the sender's and the receiver's clock after t=:
//   CHANNEL t=MONOTONIC_S utime=SENDER_US rx_us=REALTIME_US module=...
// (every message type starts with int64_t utime, big-endian after LCM's
// 8-byte type fingerprint): two listeners on two computers find the same
// message by its utime (loss), and rx_us - utime is the clocks' difference
// plus the transit (tests/twocomp).
#include <lcm/lcm-cpp.hpp>
#include <poll.h>

#include <CLI/CLI.hpp>
#include <chrono>
#include <cstdint>
#include <cstdio>
#include <iostream>
#include <set>
#include <string>
#include <vector>

#include "advee/signal_fd.hpp"
#include "advee/msgs/bus.hpp"
#include "advee/msgs/channels.hpp"
#include "advee/msgs/describe.hpp"

namespace {

std::int64_t sender_utime(const lcm::ReceiveBuffer& rb) {
  if (rb.data_size < 16) return 0;
  const auto* p = static_cast<const unsigned char*>(rb.data) + 8;
  std::uint64_t v = 0;
  for (int i = 0; i < 8; ++i) v = v << 8 | p[i];
  return static_cast<std::int64_t>(v);
}

struct Printer {
  bool stamps = false;
  void on(const lcm::ReceiveBuffer* rb, const std::string& ch) {
    std::string line = advee::msgs::describe(*rb, ch);
    if (stamps) {
      const auto rx = std::chrono::duration_cast<std::chrono::microseconds>(
                          std::chrono::system_clock::now().time_since_epoch()).count();
      const auto after_t = line.find(' ', ch.size() + 1);
      line.insert(after_t == std::string::npos ? line.size() : after_t,
                  " utime=" + std::to_string(sender_utime(*rb)) + " rx_us=" + std::to_string(rx));
    }
    std::cout << line << '\n' << std::flush;
  }
};

}  // namespace

int main(int argc, char** argv) {
  double seconds = 5;
  std::vector<std::string> channels;
  CLI::App app{
      "advee-stack-listen: prints every message of the low level's LCM channels for a while, one decoded line "
      "each: `CHANNEL t=MONOTONIC_SECONDS module=SENDER key=value ...` (the whole-stack VM tests count and "
      "compare them). Without CHANNEL arguments: every channel of advee/msgs/channels.hpp and SIM_DATA_POSE "
      "(advee-robot-sim's ground truth). The LCM URL comes from LCM_DEFAULT_URL, else /etc/advee/lcm.conf.\n\n"
      "Exit status: 0, 1 when LCM does not start, 2 on bad arguments.",
      "advee-stack-listen"};
  app.add_option("-s,--seconds", seconds, "how long to listen")->check(CLI::Range(0.1, 86400.0))->capture_default_str();
  bool stamps = false;
  app.add_flag("--stamps", stamps, "add utime=SENDER_US rx_us=REALTIME_US after t=");
  app.add_option("channels", channels, "channels to listen to (default: all)");
  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    const int rc = app.exit(e);
    return rc == 0 ? 0 : 2;
  }
  if (channels.empty()) {
    for (const auto& c : advee::msgs::kAllChannels) channels.emplace_back(c.name);
    channels.emplace_back(advee::msgs::kSimDataPose);
  }
  try {
    advee::SignalFd signals({SIGINT, SIGTERM});
    std::unique_ptr<lcm::LCM> bus;
    try {
      bus = advee::msgs::open_bus(advee::msgs::bus_url(""));
    } catch (const advee::msgs::BusUnavailable& e) {
      std::cerr << "advee-stack-listen: " << e.what() << "\n";
      return 1;
    }
    lcm::LCM& lcm = *bus;
    Printer printer;
    printer.stamps = stamps;
    std::set<std::string> unique(channels.begin(), channels.end());
    for (const auto& c : unique) lcm.subscribe(c, &Printer::on, &printer);
    const auto end = std::chrono::steady_clock::now() + std::chrono::duration<double>(seconds);
    for (;;) {
      const auto left = std::chrono::duration_cast<std::chrono::milliseconds>(end - std::chrono::steady_clock::now());
      if (left.count() <= 0) break;
      pollfd fds[2] = {{lcm.getFileno(), POLLIN, 0}, {signals.fd(), POLLIN, 0}};
      if (::poll(fds, 2, static_cast<int>(left.count())) < 0) {
        if (errno == EINTR) continue;
        throw std::system_error(errno, std::generic_category(), "poll");
      }
      if (fds[1].revents & POLLIN) break;
      if (fds[0].revents & POLLIN) lcm.handle();
    }
    return 0;
  } catch (const std::exception& e) {
    std::cerr << "advee-stack-listen: " << e.what() << "\n";
    return 1;
  }
}
