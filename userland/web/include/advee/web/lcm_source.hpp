// SPDX-License-Identifier: GPL-2.0
// Receives the bridged LCM channels on its own thread and hands each decoded
// message (message_to_json(), plus "line": msgs::describe()'s one line) to a
// callback on that thread. Stopping = destroying:
// the thread is joined within one LCM wait (100 ms).
#pragma once

#include <atomic>
#include <cstdint>
#include <functional>
#include <nlohmann/json.hpp>
#include <memory>
#include <stop_token>
#include <string>
#include <thread>
#include <vector>

namespace lcm {
class LCM;
class ReceiveBuffer;
}  // namespace lcm

namespace advee::web {

class LcmSource {
 public:
  using Sink = std::function<void(const nlohmann::json& message)>;

  // `url` "" = the robot's (advee/msgs/bus.hpp). Throws
  // msgs::BusUnavailable when LCM cannot be set up, naming the fix.
  LcmSource(const std::string& url, const std::vector<std::string>& channels, Sink sink);
  ~LcmSource();
  LcmSource(const LcmSource&) = delete;
  LcmSource& operator=(const LcmSource&) = delete;

  std::uint64_t received() const { return received_; }
  std::uint64_t undecodable() const { return undecodable_; }
  // Set when LCM's receive loop failed (the thread has ended).
  bool failed() const { return failed_; }

 private:
  static void on_message(const lcm::ReceiveBuffer* rb, const std::string& channel,
                         LcmSource* self);
  void run(std::stop_token stop);

  std::unique_ptr<lcm::LCM> lcm_;
  Sink sink_;
  std::atomic<std::uint64_t> received_{0}, undecodable_{0};
  std::atomic<bool> failed_{false};
  std::jthread thread_;  // last: joined before the members it uses go
};

}  // namespace advee::web
