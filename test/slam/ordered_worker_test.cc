// The keyframe thread's hand-over (slam/ordered_worker.h): order, back-pressure, errors.
#include "slam/ordered_worker.h"

#include <gtest/gtest.h>

#include <atomic>
#include <chrono>
#include <future>
#include <stdexcept>
#include <vector>

namespace uwbsar::slam {
namespace {

TEST(OrderedWorkerTest, ItemsAreProcessedInHandOverOrderWithOrWithoutTheThread) {
  for (const bool threaded : {false, true}) {
    std::vector<int> seen;  // written by the worker only; read after Drain
    OrderedWorker<int> worker(threaded, 2, [&](int&& i) { seen.push_back(i); });
    for (int i = 0; i < 100; ++i) worker.Push(i, i % 3);  // weights 0, 1, 2
    worker.Drain();
    ASSERT_EQ(seen.size(), 100u) << "threaded " << threaded;
    for (int i = 0; i < 100; ++i) EXPECT_EQ(seen[static_cast<std::size_t>(i)], i);
  }
}

TEST(OrderedWorkerTest, AFullQueueMakesTheFeederWaitUntilTheWorkerTakesAnItem) {
  std::promise<void> release;
  std::shared_future<void> released = release.get_future().share();
  std::atomic<int> started{0};
  OrderedWorker<int> worker(true, 2, [&](int&&) {
    ++started;
    released.wait();
  });
  worker.Push(0, 1);  // taken by the worker, which then blocks
  while (started.load() == 0) std::this_thread::sleep_for(std::chrono::milliseconds(1));
  worker.Push(1, 1);
  worker.Push(2, 1);  // queued weight 2 = the bound
  auto feeder = std::async(std::launch::async, [&] { worker.Push(3, 1); });
  // The fourth hand-over cannot return while the worker holds the first item.
  EXPECT_EQ(feeder.wait_for(std::chrono::milliseconds(200)), std::future_status::timeout);
  release.set_value();
  feeder.get();
  worker.Drain();
  EXPECT_EQ(started.load(), 4);
}

TEST(OrderedWorkerTest, TheWorkersErrorIsRethrownToTheFeederAndStopsTheWorker) {
  std::vector<int> seen;
  OrderedWorker<int> worker(true, 4, [&](int&& i) {
    if (i == 1) throw std::runtime_error("bad keyframe 1");
    seen.push_back(i);
  });
  worker.Push(0, 1);
  worker.Push(1, 1);
  EXPECT_THROW(worker.Drain(), std::runtime_error);
  EXPECT_THROW(worker.Push(2, 1), std::runtime_error);  // refused, not queued
  EXPECT_THROW(worker.RethrowError(), std::runtime_error);
  EXPECT_EQ(seen, std::vector<int>{0});
}

TEST(OrderedWorkerTest, WithoutTheThreadAnErrorReachesThePusherAtOnce) {
  OrderedWorker<int> worker(false, 1, [](int&&) { throw std::runtime_error("inline"); });
  EXPECT_THROW(worker.Push(0, 1), std::runtime_error);
}

TEST(OrderedWorkerTest, DestructionProcessesWhatIsStillQueued) {
  std::atomic<int> processed{0};
  {
    OrderedWorker<int> worker(true, 100, [&](int&&) {
      std::this_thread::sleep_for(std::chrono::milliseconds(1));
      ++processed;
    });
    for (int i = 0; i < 20; ++i) worker.Push(i, 1);
  }
  EXPECT_EQ(processed.load(), 20);
}

}  // namespace
}  // namespace uwbsar::slam
