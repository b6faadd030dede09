// SPDX-License-Identifier: GPL-2.0
#include "advee/rs485/event_dispatcher.hpp"

#include <atomic>
#include <vector>

namespace advee::rs485 {

// Shared with the cancel functions of the Subscriptions, so that a
// Subscription that outlives its transport unsubscribes harmlessly.
struct EventDispatcher::State {
  struct Entry {
    EventHandler on_event;
    ClosedHandler on_closed;
  };
  mutable std::mutex mutex;          // the map, closed
  std::mutex running;                // held while handlers run
  std::atomic<std::thread::id> dispatching_thread{};
  std::map<std::uint64_t, std::shared_ptr<Entry>> entries;
  std::uint64_t next_id = 0;
  bool closed = false;
  std::error_code close_reason;

  std::vector<std::pair<std::uint64_t, std::shared_ptr<Entry>>> snapshot() {
    std::lock_guard lock(mutex);
    return {entries.begin(), entries.end()};
  }
  bool alive(std::uint64_t id) {
    std::lock_guard lock(mutex);
    return entries.count(id) != 0;
  }
};

EventDispatcher::EventDispatcher() : state_(std::make_shared<State>()) {}
EventDispatcher::~EventDispatcher() = default;

Subscription EventDispatcher::subscribe(EventHandler on_event, ClosedHandler on_closed) {
  std::uint64_t id;
  bool closed_already;
  std::error_code why;
  {
    std::lock_guard lock(state_->mutex);
    id = state_->next_id++;
    closed_already = state_->closed;
    why = state_->close_reason;
    if (!closed_already)
      state_->entries.emplace(id, std::make_shared<State::Entry>(State::Entry{std::move(on_event), on_closed}));
  }
  if (closed_already) {
    if (on_closed) on_closed(why);
    return {};
  }
  std::weak_ptr<State> weak = state_;
  return Subscription([weak, id] {
    auto state = weak.lock();
    if (!state) return;
    {
      std::lock_guard lock(state->mutex);
      state->entries.erase(id);
    }
    // Wait for a handler that is running now, unless we are that handler.
    if (state->dispatching_thread != std::this_thread::get_id()) std::lock_guard wait(state->running);
  });
}

void EventDispatcher::dispatch(const Frame& frame) {
  std::lock_guard running(state_->running);
  state_->dispatching_thread = std::this_thread::get_id();
  for (auto& [id, entry] : state_->snapshot())
    if (entry->on_event && state_->alive(id)) entry->on_event(frame);
  state_->dispatching_thread = std::thread::id{};
}

void EventDispatcher::close(std::error_code why) {
  std::lock_guard running(state_->running);
  {
    std::lock_guard lock(state_->mutex);
    if (state_->closed) return;
    state_->closed = true;
    state_->close_reason = why;
  }
  state_->dispatching_thread = std::this_thread::get_id();
  for (auto& [id, entry] : state_->snapshot())
    if (entry->on_closed && state_->alive(id)) entry->on_closed(why);
  state_->dispatching_thread = std::thread::id{};
}

bool EventDispatcher::closed() const {
  std::lock_guard lock(state_->mutex);
  return state_->closed;
}

std::size_t EventDispatcher::subscribers() const {
  std::lock_guard lock(state_->mutex);
  return state_->entries.size();
}

}  // namespace advee::rs485
