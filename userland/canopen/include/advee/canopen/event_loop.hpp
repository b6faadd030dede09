// SPDX-License-Identifier: GPL-2.0
// One epoll loop: file descriptors, one timerfd armed at the earliest deadline
// of the registered timer sources, and an eventfd behind post() so other
// threads hand work to the loop thread. Everything the engine does runs on
// this thread; nothing else touches it.
#pragma once

#include <cstdint>
#include <functional>
#include <map>
#include <mutex>
#include <optional>
#include <thread>
#include <vector>

#include "advee/canopen/clock.hpp"
#include "advee/unique_fd.hpp"

namespace advee::canopen {

class EventLoop {
 public:
  using FdHandler = std::function<void(std::uint32_t events)>;
  using DeadlineFn = std::function<std::optional<TimePoint>()>;

  EventLoop();  // throws std::system_error
  EventLoop(const EventLoop&) = delete;
  EventLoop& operator=(const EventLoop&) = delete;

  void add_fd(int fd, std::uint32_t events, FdHandler h);
  void modify_fd(int fd, std::uint32_t events);
  void remove_fd(int fd);
  // After every wake-up each source's `poll` runs; the timerfd is armed at
  // the earliest `deadline` of all sources.
  void add_timer_source(DeadlineFn deadline, std::function<void()> poll);

  // Thread-safe.
  void post(std::function<void()> fn);
  void stop();

  // Runs until stop(). Exceptions from handlers propagate out of run().
  void run();
  // One wait + dispatch; returns false once stopped.
  bool run_once(std::optional<Duration> max_wait = std::nullopt);
  bool stopped() const { return stopped_; }

 private:
  void arm_timer();
  void drain_posted();

  UniqueFd epoll_;
  UniqueFd timer_;
  UniqueFd wake_;
  std::map<int, FdHandler> handlers_;
  struct TimerSource {
    DeadlineFn deadline;
    std::function<void()> poll;
  };
  std::vector<TimerSource> timers_;
  std::mutex mutex_;
  std::vector<std::function<void()>> posted_;
  bool stopped_ = false;
  std::optional<TimePoint> armed_;  // what the timerfd holds, to skip redundant syscalls
};

// Runs a loop on its own thread; stops and joins on destruction.
class LoopThread {
 public:
  explicit LoopThread(EventLoop& loop) : loop_(loop), thread_([this] { loop_.run(); }) {}
  ~LoopThread() {
    loop_.stop();
    if (thread_.joinable()) thread_.join();
  }
  LoopThread(const LoopThread&) = delete;
  LoopThread& operator=(const LoopThread&) = delete;

 private:
  EventLoop& loop_;
  std::thread thread_;
};

}  // namespace advee::canopen
