// SPDX-License-Identifier: GPL-2.0
// The epoll/timerfd/eventfd loop: post() from other threads, timer sources,
// stop, and the RAII thread wrapper.
#include "advee/canopen/event_loop.hpp"

#include <gtest/gtest.h>
#include <fcntl.h>
#include <sys/epoll.h>

#include <atomic>
#include <cerrno>
#include <future>
#include <system_error>

namespace advee::canopen {
namespace {

using namespace std::chrono_literals;

TEST(EventLoopTest, PostedWorkRunsOnTheLoopThreadInOrder) {
  EventLoop loop;
  std::vector<int> order;
  std::thread::id loop_thread;
  std::promise<void> done;
  {
    LoopThread t(loop);
    std::thread poster([&] {
      for (int i = 0; i < 100; ++i) loop.post([&order, i] { order.push_back(i); });
      loop.post([&] {
        loop_thread = std::this_thread::get_id();
        done.set_value();
      });
    });
    poster.join();
    ASSERT_EQ(done.get_future().wait_for(5s), std::future_status::ready);
  }
  ASSERT_EQ(order.size(), 100u);
  for (int i = 0; i < 100; ++i) EXPECT_EQ(order[static_cast<std::size_t>(i)], i);
  EXPECT_NE(loop_thread, std::this_thread::get_id());
}

TEST(EventLoopTest, TimerSourceIsPolledNoEarlierThanItsDeadline) {
  EventLoop loop;
  const TimePoint deadline = SteadyClock::now() + 20ms;
  std::optional<TimePoint> fired;
  loop.add_timer_source([&]() -> std::optional<TimePoint> { return fired ? std::nullopt : std::optional(deadline); },
                        [&] {
                          if (!fired && SteadyClock::now() >= deadline) {
                            fired = SteadyClock::now();
                            loop.stop();
                          }
                        });
  loop.post([] {});  // wakes the loop once before the deadline
  loop.run();
  ASSERT_TRUE(fired);
  EXPECT_GE(*fired, deadline);
}

TEST(EventLoopTest, FdHandlerSeesReadiness) {
  EventLoop loop;
  int p[2];
  ASSERT_EQ(::pipe(p), 0);
  UniqueFd rd(p[0]), wr(p[1]);
  std::string got;
  loop.add_fd(rd.get(), EPOLLIN, [&](std::uint32_t) {
    char buf[16];
    const ssize_t n = ::read(rd.get(), buf, sizeof buf);
    got.assign(buf, static_cast<std::size_t>(n > 0 ? n : 0));
    loop.stop();
  });
  ASSERT_EQ(::write(wr.get(), "can", 3), 3);
  loop.run();
  EXPECT_EQ(got, "can");
  loop.remove_fd(rd.get());
}

TEST(EventLoopTest, RunOnceHonoursTheMaximumWaitWhenIdle) {
  EventLoop loop;
  const TimePoint start = SteadyClock::now();
  EXPECT_TRUE(loop.run_once(1ms));
  EXPECT_GE(SteadyClock::now() - start, 1ms);
  loop.stop();
  EXPECT_FALSE(loop.run_once(1ms)) << "the posted stop ran";
  EXPECT_TRUE(loop.stopped());
  EXPECT_FALSE(loop.run_once(1ms));
}

TEST(UniqueFdTest, ClosesOnceAndMoves) {
  int p[2];
  ASSERT_EQ(::pipe(p), 0);
  ::close(p[1]);
  UniqueFd a(p[0]);
  UniqueFd b(std::move(a));
  EXPECT_FALSE(a);
  EXPECT_TRUE(b);
  const int raw = b.get();
  b.reset();
  EXPECT_EQ(::fcntl(raw, F_GETFD), -1) << "closed";
}

TEST(LoopThreadTest, AnExceptionEndsTheLoopAndReachesTheFailureHandler) {
  EventLoop loop;
  std::promise<std::string> failed;
  auto what = failed.get_future();
  {
    LoopThread thread(loop, [&](std::exception_ptr e) {
      try {
        std::rethrow_exception(e);
      } catch (const std::exception& x) {
        failed.set_value(x.what());
      }
    });
    loop.post([] { throw std::system_error(ENETDOWN, std::generic_category(), "recvmmsg(CAN)"); });
    ASSERT_EQ(what.wait_for(std::chrono::seconds(10)), std::future_status::ready);
  }  // stops and joins a loop that already ended: no std::terminate
  EXPECT_EQ(what.get(), "recvmmsg(CAN): Network is down");
}

}  // namespace
}  // namespace advee::canopen
