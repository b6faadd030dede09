// SPDX-License-Identifier: GPL-2.0
#include "advee/rs485/event_dispatcher.hpp"

#include <gtest/gtest.h>

#include <atomic>
#include <memory>
#include <thread>

#include "advee/rs485/fake_transport.hpp"
#include "advee/testing/thread_state.hpp"

namespace advee::rs485 {
namespace {

TEST(Rs485Events, EverySubscriberGetsEveryFrameUntilUnsubscribed) {
  EventDispatcher d;
  std::vector<Frame> a, b;
  auto sa = d.subscribe([&](const Frame& f) { a.push_back(f); }, {});
  auto sb = d.subscribe([&](const Frame& f) { b.push_back(f); }, {});
  d.dispatch({1, 2, 8, {3}});
  sb.reset();
  d.dispatch({4, 5, 8, {}});
  EXPECT_EQ(a.size(), 2u);
  ASSERT_EQ(b.size(), 1u);
  EXPECT_EQ(b[0], (Frame{1, 2, 8, {3}}));
  EXPECT_EQ(d.subscribers(), 1u);
}

TEST(Rs485Events, ClosedReachesSubscribersOnceAndLateOnesAtOnce) {
  EventDispatcher d;
  int closed = 0;
  std::error_code why;
  auto s = d.subscribe([](const Frame&) {}, [&](std::error_code ec) { ++closed; why = ec; });
  d.close(std::make_error_code(std::errc::io_error));
  d.close(std::make_error_code(std::errc::io_error));
  EXPECT_EQ(closed, 1);
  EXPECT_EQ(why, std::errc::io_error);
  bool late = false;
  auto s2 = d.subscribe([](const Frame&) {}, [&](std::error_code) { late = true; });
  EXPECT_TRUE(late);
  EXPECT_FALSE(s2);
}

TEST(Rs485Events, UnsubscribingFromInsideTheHandlerDoesNotDeadlock) {
  EventDispatcher d;
  int calls = 0;
  Subscription s;
  s = d.subscribe([&](const Frame&) { ++calls; s.reset(); }, {});
  d.dispatch({});
  d.dispatch({});
  EXPECT_EQ(calls, 1);
}

TEST(Rs485Events, ResetWaitsForARunningHandler) {
  EventDispatcher d;
  std::atomic<bool> in_handler{false}, release{false}, finished{false};
  auto s = d.subscribe(
      [&](const Frame&) {
        in_handler = true;
        while (!release) std::this_thread::yield();
        finished = true;
      },
      {});
  std::thread producer([&] { d.dispatch({}); });
  while (!in_handler) std::this_thread::yield();
  // Release the handler only once reset() is blocked waiting for it, so
  // that the wait is what is tested.
  const pid_t main_tid = advee::testing::current_tid();
  bool reset_blocked = false;
  std::thread releaser([&] {
    reset_blocked = advee::testing::wait_until_asleep(main_tid);
    release = true;
  });
  s.reset();
  // After reset() the handler is not running any more.
  EXPECT_TRUE(finished);
  producer.join();
  releaser.join();
  EXPECT_TRUE(reset_blocked);
}

TEST(Rs485Events, SubscriptionOutlivingTheDispatcherIsHarmless) {
  // The handlers hold this token: whoever keeps them alive shows in its count.
  auto token = std::make_shared<int>(0);
  bool closed_called = false;
  Subscription s;
  {
    EventDispatcher d;
    s = d.subscribe([token](const Frame&) {}, [token, &closed_called](std::error_code) { closed_called = true; });
    ASSERT_TRUE(s);
    EXPECT_EQ(token.use_count(), 3);
  }
  // The dispatcher took its subscribers with it; the subscription does not
  // keep them (nor the dispatcher's state) alive.
  EXPECT_EQ(token.use_count(), 1);
  EXPECT_TRUE(s);
  s.reset();  // must not touch the freed dispatcher (ASan would report it)
  EXPECT_FALSE(s);
  EXPECT_FALSE(closed_called);
}

TEST(Rs485FakeTransport, RecordsRequestsAndAnswersBroadcastWithoutResponder) {
  FakeTransport t;
  Request noack(3, 1);
  noack.no_ack = true;
  EXPECT_EQ(t.transact({3, 1}).error, Outcome::timeout);
  EXPECT_TRUE(t.transact({kBroadcast, 0xFF}).ok());
  EXPECT_TRUE(t.transact(noack).ok());
  ASSERT_EQ(t.requests().size(), 3u);
  EXPECT_EQ(t.requests()[1].addr, kBroadcast);
}

}  // namespace
}  // namespace advee::rs485
