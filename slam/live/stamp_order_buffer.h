// Puts messages from several independent streams (two radar topics and odometry, each
// taken from its own DDS reader) back into stamp order before SLAM and the recording see
// them, so a live ROS 2 run is fed in the order `uwbsar map` reads its recording.
// A message is released once it has waited `window_ns` of wall time, in stamp order: any
// message of another stream that arrives within that time with an earlier stamp goes out
// before it. Waiting in wall time (not "until a message stamped window_ns later came")
// keeps bursts in order: after a stall, samples of all streams arrive together and are
// sorted. A message older than one already released is "late": released at once, flagged.
// At the start, streams are matched one by one (DDS discovery), so one stream's first
// messages may come long after another's: with `streams` > 0, nothing is released until every
// stream has delivered a message or `startup_hold_ns` passed since the first one; a stream
// found late then still goes out in stamp order, instead of its first messages being late
// (a live run that drops the scans before its first odometry, which its recording replays
// in stamp order and images).
#pragma once

#include <algorithm>
#include <cstdint>
#include <functional>
#include <map>
#include <mutex>
#include <utility>
#include <vector>

namespace uwbsar::slam {

template <class T>
class StampOrderBuffer {
 public:
  /// `release(item, late)` is called in stamp order (under the buffer's lock: keep it short).
  /// `streams` > 0: the startup hold (above) over streams 0 .. streams - 1.
  StampOrderBuffer(std::int64_t window_ns, std::function<void(T&&, bool late)> release,
                   int streams = 0, std::int64_t startup_hold_ns = 0)
      : window_ns_(window_ns),
        release_(std::move(release)),
        startup_hold_ns_(startup_hold_ns),
        waiting_for_(streams > 0 ? std::vector<bool>(static_cast<std::size_t>(streams), true)
                                 : std::vector<bool>{}),
        started_(streams <= 0) {}

  /// `stamp_ns`: the message's stamp; `now_ns`: a monotonic wall clock; `stream`: which
  /// stream it came from (for the startup hold; ignored without one).
  void Push(std::int64_t stamp_ns, std::int64_t now_ns, T&& item, int stream = -1) {
    std::lock_guard<std::mutex> lock(mutex_);
    if (!started_) NoteStartup(stream, now_ns);
    if (released_any_ && stamp_ns < last_released_ns_) {
      ++late_;
      release_(std::move(item), true);
      return;
    }
    pending_.emplace(std::make_pair(stamp_ns, sequence_++), Entry{now_ns, std::move(item)});
    ReleaseLocked(now_ns, false);
  }
  /// Releases what waited long enough (call periodically).
  void Poll(std::int64_t now_ns) {
    std::lock_guard<std::mutex> lock(mutex_);
    if (!started_ && first_push_ns_ >= 0) NoteStartup(-1, now_ns);
    ReleaseLocked(now_ns, false);
  }
  /// Releases everything (end of run).
  void Flush() {
    std::lock_guard<std::mutex> lock(mutex_);
    ReleaseLocked(0, true);
  }
  long long late() const {
    std::lock_guard<std::mutex> lock(mutex_);
    return late_;
  }

 private:
  struct Entry {
    std::int64_t arrival_ns;
    T item;
  };
  /// Startup: `stream` delivered (-1: none); starts when every stream has, or the hold is over.
  void NoteStartup(int stream, std::int64_t now_ns) {
    if (first_push_ns_ < 0) first_push_ns_ = now_ns;
    if (stream >= 0 && static_cast<std::size_t>(stream) < waiting_for_.size())
      waiting_for_[static_cast<std::size_t>(stream)] = false;
    started_ = std::none_of(waiting_for_.begin(), waiting_for_.end(), [](bool w) { return w; }) ||
               now_ns - first_push_ns_ >= startup_hold_ns_;
  }
  void ReleaseLocked(std::int64_t now_ns, bool all) {
    if (!started_ && !all) return;
    while (!pending_.empty()) {
      auto it = pending_.begin();
      const std::int64_t stamp = it->first.first;
      // The oldest stamp goes first, once it waited the window (`all`: end of run).
      const bool due = all || now_ns - it->second.arrival_ns >= window_ns_;
      if (!due) break;
      last_released_ns_ = stamp;
      released_any_ = true;
      T item = std::move(it->second.item);
      pending_.erase(it);
      release_(std::move(item), false);
    }
  }

  const std::int64_t window_ns_;
  std::function<void(T&&, bool)> release_;
  const std::int64_t startup_hold_ns_;
  std::vector<bool> waiting_for_;  ///< startup: streams not heard from yet
  bool started_;
  std::int64_t first_push_ns_ = -1;
  mutable std::mutex mutex_;
  std::map<std::pair<std::int64_t, std::uint64_t>, Entry> pending_;  ///< (stamp, arrival seq)
  std::uint64_t sequence_ = 0;
  std::int64_t last_released_ns_ = 0;
  bool released_any_ = false;
  long long late_ = 0;
};

}  // namespace uwbsar::slam
