#include "tools/stamp_order_buffer.h"

#include <gtest/gtest.h>

#include <vector>

namespace uwbsar::tools {
namespace {

constexpr std::int64_t kMs = 1000000;

struct Released {
  std::vector<int> items;
  std::vector<bool> late;
};

StampOrderBuffer<int> MakeBuffer(Released* out, std::int64_t window_ns = 50 * kMs) {
  return StampOrderBuffer<int>(window_ns, [out](int&& item, bool late) {
    out->items.push_back(item);
    out->late.push_back(late);
  });
}

TEST(StampOrderBufferTest, InterleavedStreamsComeOutInStampOrder) {
  Released out;
  auto buffer = MakeBuffer(&out);
  // Two streams taken in bursts: stream A up to 40 ms, then stream B from 5 ms.
  buffer.Push(10 * kMs, 0, 10);
  buffer.Push(20 * kMs, 0, 20);
  buffer.Push(40 * kMs, 0, 40);
  buffer.Push(5 * kMs, 0, 5);
  buffer.Push(25 * kMs, 0, 25);
  EXPECT_TRUE(out.items.empty());  // nothing is 50 ms older than the newest yet
  buffer.Push(70 * kMs, 0, 70);    // releases everything up to 20 ms
  EXPECT_EQ(out.items, (std::vector<int>{5, 10, 20}));
  buffer.Flush();
  EXPECT_EQ(out.items, (std::vector<int>{5, 10, 20, 25, 40, 70}));
  EXPECT_EQ(buffer.late(), 0);
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
  buffer.Push(200 * kMs, 0, 200);  // releases 100
  buffer.Push(90 * kMs, 0, 90);    // older than what went out
  ASSERT_EQ(out.items, (std::vector<int>{100, 90}));
  EXPECT_EQ(out.late, (std::vector<bool>{false, true}));
  EXPECT_EQ(buffer.late(), 1);
}

}  // namespace
}  // namespace uwbsar::tools
