// A worker thread that processes hand-over items strictly in order, behind a bounded FIFO:
// the keyframe thread of SlamSystem and LocalizePipeline (slam.keyframe_thread,
// slam.keyframe_queue_size). Without a thread, Push processes on the caller's thread, so a
// result never depends on the threading as long as `process` reads nothing the feeder writes.
#pragma once

#include <condition_variable>
#include <deque>
#include <exception>
#include <functional>
#include <mutex>
#include <thread>
#include <utility>

namespace uwbsar::slam {

template <typename Item>
class OrderedWorker {
 public:
  using Process = std::function<void(Item&&)>;

  /// `threaded` false: Push runs `process` at once on the caller's thread. Otherwise items go
  /// to one worker thread; Push waits while the weight queued (not yet taken) is at least
  /// `max_weight` (back-pressure keeps memory bounded when the feeder is faster).
  OrderedWorker(bool threaded, int max_weight, Process process)
      : max_weight_(max_weight), process_(std::move(process)) {
    if (threaded) worker_ = std::thread([this] { Loop(); });
  }

  /// Processes what is still queued (unless an error stopped the worker), then joins.
  ~OrderedWorker() {
    if (!worker_.joinable()) return;
    {
      std::lock_guard<std::mutex> lock(mutex_);
      stopping_ = true;
    }
    changed_.notify_all();
    worker_.join();
  }

  OrderedWorker(const OrderedWorker&) = delete;
  OrderedWorker& operator=(const OrderedWorker&) = delete;

  bool threaded() const { return worker_.joinable(); }

  /// Hands `item` (counted as `weight` against the bound) over. Rethrows an error the worker
  /// met on an earlier item before this call queued (then `item` is not queued); the worker
  /// takes no item after an error.
  void Push(Item item, int weight) {
    if (!threaded()) {
      process_(std::move(item));
      return;
    }
    {
      std::unique_lock<std::mutex> lock(mutex_);
      changed_.wait(lock, [this] { return queued_weight_ < max_weight_ || error_; });
      // Checked before queueing, under the lock: an error of `item` itself reaches the caller
      // from a later Push or Drain, never from this one, whatever the thread timing.
      if (error_) std::rethrow_exception(error_);
      queue_.push_back({std::move(item), weight});
      queued_weight_ += weight;
    }
    changed_.notify_all();
  }

  /// Waits until every item handed over is processed; rethrows the worker's error.
  void Drain() {
    if (threaded()) {
      std::unique_lock<std::mutex> lock(mutex_);
      changed_.wait(lock, [this] { return (queue_.empty() && !busy_) || error_; });
    }
    RethrowError();
  }

  /// Rethrows the error the worker met, if any (any thread).
  void RethrowError() {
    std::exception_ptr error;
    {
      std::lock_guard<std::mutex> lock(mutex_);
      error = error_;
    }
    if (error) std::rethrow_exception(error);
  }

 private:
  struct Queued {
    Item item;
    int weight = 0;
  };

  void Loop() {
    while (true) {
      Queued next;
      {
        std::unique_lock<std::mutex> lock(mutex_);
        changed_.wait(lock, [this] { return stopping_ || !queue_.empty(); });
        if (queue_.empty() || error_) return;  // stopping with nothing left, or failed
        next = std::move(queue_.front());
        queue_.pop_front();
        queued_weight_ -= next.weight;
        busy_ = true;
      }
      changed_.notify_all();
      std::exception_ptr error;
      try {
        process_(std::move(next.item));
      } catch (...) {
        error = std::current_exception();
      }
      {
        std::lock_guard<std::mutex> lock(mutex_);
        busy_ = false;
        if (error) error_ = error;
      }
      changed_.notify_all();
    }
  }

  const int max_weight_;
  const Process process_;
  // Guarded by mutex_ (waited on with changed_); never held while `process_` runs.
  std::mutex mutex_;
  std::condition_variable changed_;
  std::deque<Queued> queue_;
  int queued_weight_ = 0;
  bool busy_ = false;
  bool stopping_ = false;
  std::exception_ptr error_;
  std::thread worker_;  // last: started after, and joined before, everything above
};

}  // namespace uwbsar::slam
