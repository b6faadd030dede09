// SPDX-License-Identifier: GPL-2.0
// The last minutes of the messages the page plots (poses, temperatures,
// speeds), replayed to a browser when it connects so that its trails and time
// plots start filled. Bounded in time and in count.
#pragma once

#include <cstddef>
#include <deque>
#include <string>

namespace advee::web {

class History {
 public:
  History(double window_s, std::size_t max_entries) : window_s_(window_s), max_(max_entries) {}
  // `t` in seconds on any monotonic clock; older entries than t - window go.
  void add(double t, std::string payload);
  const std::deque<std::string>& payloads() const { return payloads_; }
  std::size_t size() const { return payloads_.size(); }

 private:
  double window_s_;
  std::size_t max_;
  std::deque<double> times_;
  std::deque<std::string> payloads_;
};

// Channels worth replaying: what the page draws over time.
bool kept_in_history(const std::string& channel);

}  // namespace advee::web
