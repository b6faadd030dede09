// SPDX-License-Identifier: GPL-2.0
// One epoll loop: file descriptors, one timerfd armed at the earliest deadline
// of the registered timer sources, and an eventfd behind post() so other
// threads hand work to the loop thread. Everything the engine does runs on
// this thread; nothing else touches it.
#pragma once

#include <cstdint>
#include <exception>
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

// Runs a loop on its own thread; stops and joins on destruction. An
// exception out of a handler ends the loop and goes to `on_failure` on the
// loop's thread (e.g. recvmmsg's ENETDOWN when the interface goes down); it
// never reaches std::terminate. Without a handler it is dropped.
class LoopThread {
 public:
  using FailureHandler = std::function<void(std::exception_ptr)>;
  explicit LoopThread(EventLoop& loop, FailureHandler on_failure = nullptr)
      : loop_(loop), on_failure_(std::move(on_failure)), thread_([this] { run(); }) {}
  ~LoopThread() {
    loop_.stop();
    if (thread_.joinable()) thread_.join();
  }
  LoopThread(const LoopThread&) = delete;
  LoopThread& operator=(const LoopThread&) = delete;

 private:
  void run() {
    try {
      loop_.run();
    } catch (...) {
      if (on_failure_) on_failure_(std::current_exception());
    }
  }

  EventLoop& loop_;
  FailureHandler on_failure_;
  std::thread thread_;  // last: started once the rest exists
};

}  // namespace advee::canopen
