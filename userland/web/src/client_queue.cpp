// SPDX-License-Identifier: GPL-2.0
#include "advee/web/client_queue.hpp"

namespace advee::web {

void ClientQueue::push(const std::string& key, std::string payload) {
  if (const auto it = by_key_.find(key); it != by_key_.end()) {
    bytes_ -= it->second->payload.size();
    bytes_ += payload.size();
    it->second->payload = std::move(payload);
    ++dropped_;
    return;
  }
  if (max_keys_ > 0 && order_.size() >= max_keys_) {
    bytes_ -= order_.front().payload.size();
    by_key_.erase(order_.front().key);
    order_.pop_front();
    ++dropped_;
  }
  bytes_ += payload.size();
  order_.push_back(Entry{key, std::move(payload)});
  by_key_.emplace(key, std::prev(order_.end()));
}

std::vector<std::string> ClientQueue::take_all() {
  std::vector<std::string> out;
  out.reserve(order_.size());
  for (auto& e : order_) out.push_back(std::move(e.payload));
  order_.clear();
  by_key_.clear();
  bytes_ = 0;
  return out;
}

}  // namespace advee::web
