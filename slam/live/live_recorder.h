// The recording and hand-off half of `uwbsar run` (slam/live/live_runner.h), shared by every
// source (serial devices, ROS 2 over DDS). A source produces LiveMessages; the
// Dispatcher stamps each one (or keeps the source's stamp) and hands it to the Recorder,
// which writes every message to a ROS 2 bag in that order and never drops one, and to
// the bounded SLAM queue, which drops the oldest message from processing (counted) when
// SLAM falls behind.
#pragma once

#include <atomic>
#include <chrono>
#include <condition_variable>
#include <deque>
#include <memory>
#include <mutex>
#include <string>
#include <thread>
#include <vector>

#include "core/message.h"
#include "core/types.h"
#include "drivers/live/host_clock.h"
#include "drivers/rosbag/bag_writer.h"
#include "slam/app_config.h"

namespace uwbsar::slam {

using SteadyClock = std::chrono::steady_clock;

/// The recording's topic of run events (faults, GPIO, start and stop): std_msgs/String.
inline constexpr const char* kEventTopic = "/uwbsar/events";

/// A Message (core/message.h) as the live runtime passes it on: stamp_ns is the recording's
/// log time and SLAM's stamp; live sources produce scans, odometry and events.
struct LiveMessage : Message {
  bool for_slam = true;  ///< false: recorded only (e.g. a duplicate odometry sample)
  SteadyClock::time_point arrival;
};

/// Writes every message it is given to the bag, in the order given, on its own thread;
/// durable at least every live.recording_flush_period_s. Never drops a message.
class Recorder {
 public:
  Recorder(const Config& config, const std::string& dir);
  ~Recorder() { Close(); }
  void Push(const LiveMessage& msg);
  /// Writes what is queued, closes the bag (renamed from .partial). Idempotent.
  void Close();
  long long written() const { return written_; }
  std::string path() const { return writer_->path(); }

 private:
  void Loop();
  void Write(const LiveMessage& m);

  double period_s_;
  std::unique_ptr<rosbag::BagWriter> writer_;
  std::vector<int> radar_topics_;
  int odometry_topic_ = 0, event_topic_ = 0;
  rosbag::Float32MultiArray array_;
  std::vector<std::uint8_t> cdr_;
  std::thread thread_;
  std::mutex mutex_;
  std::condition_variable wake_;
  std::deque<LiveMessage> queue_;
  bool stop_ = false;
  std::atomic<long long> written_{0};
};

/// Puts messages in one order and fans them out to the recorder and the SLAM queue.
class Dispatcher {
 public:
  /// Messages dispatched before a recorder is attached are held and recorded first.
  Dispatcher(live::HostClock* clock, std::size_t capacity) : clock_(clock), capacity_(capacity) {}

  /// Attaches the recorder (once); what was held is pushed to it in order.
  void AttachRecorder(Recorder* recorder);
  /// Stamps `msg` on the host clock (serial drivers) and dispatches it.
  void Publish(LiveMessage&& msg) { Dispatch(std::move(msg), true); }
  /// Dispatches `msg` with the stamp its source gave it (ROS 2: the publisher's clock).
  void PublishStamped(LiveMessage&& msg) { Dispatch(std::move(msg), false); }
  /// Records a run event, stamped on the host clock.
  void Event(const std::string& text);
  /// Waits up to `timeout` for a message for SLAM; false when none came.
  bool Pop(LiveMessage* out, std::chrono::milliseconds timeout);
  long long dropped() const { return dropped_; }
  TimestampNs Now() const { return clock_->Now(); }

 private:
  void Dispatch(LiveMessage&& msg, bool restamp);

  live::HostClock* clock_;
  Recorder* recorder_ = nullptr;
  std::vector<LiveMessage> held_;  ///< before the recorder was attached
  std::size_t capacity_;
  std::mutex mutex_;
  std::condition_variable wake_;
  std::deque<LiveMessage> queue_;
  std::atomic<long long> dropped_{0};
};

/// rosbag2_<date>-<time>, like `ros2 bag record`.
std::string DefaultRecordingName();

}  // namespace uwbsar::slam
