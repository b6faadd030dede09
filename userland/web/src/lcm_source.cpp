// SPDX-License-Identifier: GPL-2.0
#include "advee/web/lcm_source.hpp"

#include <lcm/lcm-cpp.hpp>
#include <stdexcept>

#include "advee/msgs/bus.hpp"
#include "advee/msgs/describe.hpp"
#include "advee/web/message_json.hpp"

namespace advee::web {

LcmSource::LcmSource(const std::string& url, const std::vector<std::string>& channels, Sink sink)
    : lcm_(msgs::open_bus(msgs::bus_url(url))), sink_(std::move(sink)) {
  // LCM anchors the (regular expression) name; ours are plain words.
  for (const auto& ch : channels) lcm_->subscribeFunction(ch, &LcmSource::on_message, this);
  thread_ = std::jthread([this](std::stop_token st) { run(st); });
}

LcmSource::~LcmSource() {
  thread_.request_stop();
  if (thread_.joinable()) thread_.join();
}

void LcmSource::on_message(const lcm::ReceiveBuffer* rb, const std::string& channel,
                           LcmSource* self) {
  ++self->received_;
  auto j = message_to_json(channel, rb->data, rb->data_size);
  if (!j) {
    ++self->undecodable_;
    return;
  }
  // The page's list of recent messages shows the same line as the console tools.
  (*j)["line"] = msgs::describe(*rb, channel);
  self->sink_(*j);
}

void LcmSource::run(std::stop_token stop) {
  while (!stop.stop_requested()) {
    if (lcm_->handleTimeout(100) < 0) {
      failed_ = true;
      return;
    }
  }
}

}  // namespace advee::web
