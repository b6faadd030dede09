// SPDX-License-Identifier: GPL-2.0
// A slow browser's queue stays bounded and keeps the newest value per key.
#include "advee/web/client_queue.hpp"

#include <gtest/gtest.h>

namespace advee::web {
namespace {

TEST(ClientQueue, KeepsArrivalOrder) {
  ClientQueue q;
  q.push("A", "a1");
  q.push("B", "b1");
  q.push("C", "c1");
  EXPECT_EQ(q.take_all(), (std::vector<std::string>{"a1", "b1", "c1"}));
  EXPECT_EQ(q.pending(), 0u);
  EXPECT_EQ(q.dropped(), 0u);
}

TEST(ClientQueue, NewerReplacesOlderOfTheSameKeyAndCountsTheDrop) {
  ClientQueue q;
  q.push("ODO", "odo1");
  q.push("TEMP", "t1");
  q.push("ODO", "odo2");
  q.push("ODO", "odo3");
  EXPECT_EQ(q.pending(), 2u);
  EXPECT_EQ(q.dropped(), 2u);
  EXPECT_EQ(q.take_all(), (std::vector<std::string>{"odo3", "t1"}));
  q.push("ODO", "odo4");  // nothing pending under ODO any more: no drop
  EXPECT_EQ(q.dropped(), 2u);
}

TEST(ClientQueue, BoundedUnderAFloodOfOneChannel) {
  ClientQueue q;
  for (int i = 0; i < 100000; ++i) q.push("LL_DATA_SRFS", std::string(100, 'x') + std::to_string(i));
  EXPECT_EQ(q.pending(), 1u);
  EXPECT_LT(q.pending_bytes(), 200u);
  EXPECT_EQ(q.dropped(), 99999u);
  EXPECT_EQ(q.take_all().front(), std::string(100, 'x') + "99999");
}

TEST(ClientQueue, KeyCapEvictsTheOldest) {
  ClientQueue q(3);
  q.push("a", "1");
  q.push("b", "2");
  q.push("c", "3");
  q.push("d", "4");
  EXPECT_EQ(q.pending(), 3u);
  EXPECT_EQ(q.dropped(), 1u);
  EXPECT_EQ(q.take_all(), (std::vector<std::string>{"2", "3", "4"}));
}

TEST(ClientQueue, PendingBytesFollowReplacements) {
  ClientQueue q;
  q.push("a", "12345");
  q.push("b", "12");
  q.push("a", "1");
  EXPECT_EQ(q.pending_bytes(), 3u);
  q.take_all();
  EXPECT_EQ(q.pending_bytes(), 0u);
}

}  // namespace
}  // namespace advee::web
