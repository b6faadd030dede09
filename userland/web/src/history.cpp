// SPDX-License-Identifier: GPL-2.0
#include "advee/web/history.hpp"

namespace advee::web {

void History::add(double t, std::string payload) {
  times_.push_back(t);
  payloads_.push_back(std::move(payload));
  while (!times_.empty() && (times_.front() < t - window_s_ || times_.size() > max_)) {
    times_.pop_front();
    payloads_.pop_front();
  }
}

bool kept_in_history(const std::string& channel) {
  return channel == "WEB_ODO_POSE" || channel == "SIM_DATA_POSE" || channel == "LL_DATA_ODO" ||
         channel == "LL_DATA_DRIVES" || channel == "LL_DATA_TEMPERATURE";
}

}  // namespace advee::web
