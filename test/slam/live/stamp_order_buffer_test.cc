#include "slam/live/stamp_order_buffer.h"

#include <gtest/gtest.h>

#include <vector>

namespace uwbsar::tools {
namespace {

constexpr std::int64_t kMs = 1000000;

struct Released {
  std::vector<int> items;
  std::vector<bool> late;
};

/// A buffer with a 50 ms window that records what it releases into `out`; `streams` and
/// `startup_hold_ns` as in StampOrderBuffer (0: no startup hold).
slam::StampOrderBuffer<int> MakeBuffer(Released* out, int streams = 0,
                                       std::int64_t startup_hold_ns = 0) {
  return slam::StampOrderBuffer<int>(
      50 * kMs,
      [out](int&& item, bool late) {
        out->items.push_back(item);
        out->late.push_back(late);
      },
      streams, startup_hold_ns);
}

TEST(StampOrderBufferTest, InterleavedStreamsComeOutInStampOrder) {
  Released out;
  auto buffer = MakeBuffer(&out);
  // Two streams taken in bursts: stream A up to 40 ms, then stream B from 5 ms.
  buffer.Push(10 * kMs, 0, 10);
  buffer.Push(20 * kMs, 1 * kMs, 20);
  buffer.Push(40 * kMs, 2 * kMs, 40);
  buffer.Push(5 * kMs, 3 * kMs, 5);
  buffer.Push(25 * kMs, 30 * kMs, 25);
  buffer.Poll(49 * kMs);
  EXPECT_TRUE(out.items.empty());  // nothing waited 50 ms yet
  buffer.Poll(53 * kMs);           // 5, 10, 20 and 40 waited; 25 arrived at 30 ms
  EXPECT_EQ(out.items, (std::vector<int>{5, 10, 20}));
  buffer.Poll(80 * kMs);
  EXPECT_EQ(out.items, (std::vector<int>{5, 10, 20, 25, 40}));
  EXPECT_EQ(buffer.late(), 0);
}

TEST(StampOrderBufferTest, ABurstAfterAStallIsSortedWhateverItsStampSpan) {
  Released out;
  auto buffer = MakeBuffer(&out);
  // The reading thread stalled for 300 ms: one stream's backlog, then the other's.
  for (int i = 0; i < 30; ++i) buffer.Push(i * 10 * kMs, 1000 * kMs, 1000 + i);
  for (int i = 0; i < 15; ++i) buffer.Push(i * 20 * kMs + kMs, 1001 * kMs, 2000 + i);
  buffer.Poll(1051 * kMs);
  ASSERT_EQ(out.items.size(), 45u);
  EXPECT_EQ(buffer.late(), 0);
  EXPECT_EQ(out.items[0], 1000);
  EXPECT_EQ(out.items[1], 2000);  // stamped 1 ms
}

TEST(StampOrderBufferTest, AStreamMatchedLateStillStartsInStampOrder) {
  // Three streams (two radars, odometry); DDS matched the odometry reader 300 ms after the
  // radars'. Without the startup hold, the radars' first scans would go out after 50 ms and
  // the odometry's first samples, stamped before them, would come late.
  Released out;
  auto buffer = MakeBuffer(&out, /*streams=*/3, /*startup_hold_ns=*/2000 * kMs);
  for (int i = 0; i < 10; ++i) {
    buffer.Push((10 + 10 * i) * kMs, 10 * i * kMs, 100 + i, 0);
    buffer.Push((15 + 10 * i) * kMs, 10 * i * kMs, 200 + i, 1);
  }
  buffer.Poll(250 * kMs);
  EXPECT_TRUE(out.items.empty());  // the odometry has not been heard from
  buffer.Push(0, 300 * kMs, 0, 2);
  buffer.Push(12 * kMs, 300 * kMs, 1, 2);
  buffer.Poll(351 * kMs);
  ASSERT_EQ(out.items.size(), 22u);
  EXPECT_EQ(buffer.late(), 0);
  EXPECT_EQ(out.items[0], 0);  // stamped 0: first
  EXPECT_EQ(out.items[1], 100);
  EXPECT_EQ(out.items[2], 1);  // stamped 12 ms
  EXPECT_EQ(out.items[3], 200);
}

TEST(StampOrderBufferTest, AStreamThatNeverComesHoldsTheStartOnlyThatLong) {
  Released out;
  auto buffer = MakeBuffer(&out, /*streams=*/2, /*startup_hold_ns=*/500 * kMs);
  buffer.Push(10 * kMs, 0, 1, 0);
  buffer.Push(20 * kMs, 100 * kMs, 2, 0);
  buffer.Poll(499 * kMs);
  EXPECT_TRUE(out.items.empty());
  buffer.Poll(500 * kMs);  // stream 1 is silent: the hold is over
  EXPECT_EQ(out.items, (std::vector<int>{1, 2}));
  buffer.Push(30 * kMs, 510 * kMs, 3, 0);  // from here the window alone
  buffer.Poll(559 * kMs);
  EXPECT_EQ(out.items.size(), 2u);
  buffer.Poll(560 * kMs);
  EXPECT_EQ(out.items, (std::vector<int>{1, 2, 3}));
}

TEST(StampOrderBufferTest, EqualStampsKeepArrivalOrder) {
  Released out;
  auto buffer = MakeBuffer(&out);
  buffer.Push(10 * kMs, 0, 1);
  buffer.Push(10 * kMs, 0, 2);
  buffer.Flush();
  EXPECT_EQ(out.items, (std::vector<int>{1, 2}));
}

TEST(StampOrderBufferTest, AStoppedStreamDoesNotHoldTheRestLongerThanTheWindow) {
  Released out;
  auto buffer = MakeBuffer(&out);
  buffer.Push(10 * kMs, 0, 10);
  buffer.Poll(49 * kMs);
  EXPECT_TRUE(out.items.empty());
  buffer.Poll(50 * kMs);  // waited the window in wall time
  EXPECT_EQ(out.items, (std::vector<int>{10}));
}

TEST(StampOrderBufferTest, ASampleOlderThanOneReleasedIsPassedOnFlaggedLate) {
  Released out;
  auto buffer = MakeBuffer(&out);
  buffer.Push(100 * kMs, 0, 100);
  buffer.Poll(50 * kMs);                // releases 100
  buffer.Push(90 * kMs, 60 * kMs, 90);  // older than what went out
  ASSERT_EQ(out.items, (std::vector<int>{100, 90}));
  EXPECT_EQ(out.late, (std::vector<bool>{false, true}));
  EXPECT_EQ(buffer.late(), 1);
}

}  // namespace
}  // namespace uwbsar::tools
