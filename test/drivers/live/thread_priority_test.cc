#include "drivers/live/thread_priority.h"

#include <gtest/gtest.h>
#include <pthread.h>
#include <sched.h>

#include <string>
#include <thread>

namespace uwbsar::live {
namespace {

int CurrentPolicy() {
  int policy = -1;
  sched_param param{};
  pthread_getschedparam(pthread_self(), &policy, &param);
  return policy;
}

TEST(ThreadPriorityTest, ZeroLeavesTheThreadAtNormalPriority) {
  int policy = -1;
  std::string error = "unset";
  std::thread t([&] {
    error = SetCurrentThreadRealtime(0);
    policy = CurrentPolicy();
  });
  t.join();
  EXPECT_EQ(error, "");
  EXPECT_EQ(policy, SCHED_OTHER);
}

TEST(ThreadPriorityTest, PriorityOutsideTheFifoRangeIsRefusedWithTheRange) {
  std::string error;
  int policy = -1;
  std::thread t([&] {
    error = SetCurrentThreadRealtime(150);
    policy = CurrentPolicy();
  });
  t.join();
  EXPECT_NE(error.find("outside SCHED_FIFO's 1..99"), std::string::npos) << error;
  EXPECT_EQ(policy, SCHED_OTHER);
}

// Either the thread runs under SCHED_FIFO, or the reason it may not is given and the
// thread is unchanged: never a silent half-way state.
TEST(ThreadPriorityTest, FifoIsTakenOrTheRefusalIsExplained) {
  std::string error;
  int policy = -1;
  std::thread t([&] {
    error = SetCurrentThreadRealtime(10);
    policy = CurrentPolicy();
  });
  t.join();
  if (error.empty()) {
    EXPECT_EQ(policy, SCHED_FIFO);
  } else {
    EXPECT_NE(error.find("SCHED_FIFO 10: "), std::string::npos) << error;
    EXPECT_EQ(policy, SCHED_OTHER);
  }
}

}  // namespace
}  // namespace uwbsar::live
