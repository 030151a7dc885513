#include "slam/live/live_recorder.h"

#include <ctime>

#include "drivers/rosbag/cdr_writer.h"
#include "drivers/sim/sim_bag_writer.h"
#include "slam/app_config.h"

namespace uwbsar::slam {

Recorder::Recorder(const Config& config, const std::string& dir)
    : period_s_(config.live.recording_flush_period_s) {
  rosbag::BagWriterOptions options;
  options.storage = config.live.recording_storage;
  options.flush_period_s = period_s_;
  writer_ = std::make_unique<rosbag::BagWriter>(dir, options);
  for (const RadarConfig& r : config.radars) {
    radar_topics_.push_back(writer_->AddTopic(r.topic, "std_msgs/msg/Float32MultiArray"));
  }
  odometry_topic_ = writer_->AddTopic(config.slam.odometry_topic, "nav_msgs/msg/Odometry");
  event_topic_ = writer_->AddTopic(kEventTopic, "std_msgs/msg/String", "string data\n");
  writer_->Flush();
  thread_ = std::thread([this] { Loop(); });
}

void Recorder::Push(const LiveMessage& msg) {
  {
    std::lock_guard<std::mutex> lock(mutex_);
    queue_.push_back(msg);
  }
  wake_.notify_one();
}

void Recorder::Close() {
  if (!thread_.joinable()) return;
  {
    std::lock_guard<std::mutex> lock(mutex_);
    stop_ = true;
  }
  wake_.notify_one();
  thread_.join();
  writer_->Close();
}

void Recorder::Loop() {
  auto last_flush = SteadyClock::now();
  std::deque<LiveMessage> batch;
  while (true) {
    bool stopping = false;
    {
      std::unique_lock<std::mutex> lock(mutex_);
      wake_.wait_for(lock, std::chrono::duration<double>(period_s_ / 2),
                     [this] { return stop_ || !queue_.empty(); });
      batch.swap(queue_);
      stopping = stop_;
    }
    for (const LiveMessage& m : batch) Write(m);
    batch.clear();
    if (SteadyClock::now() - last_flush >= std::chrono::duration<double>(period_s_)) {
      writer_->Flush();
      last_flush = SteadyClock::now();
    }
    if (stopping) break;
  }
}

void Recorder::Write(const LiveMessage& m) {
  switch (m.kind) {
    case Message::Kind::kRadarScan: {
      array_.data = m.scan.samples;
      writer_->WriteMessage(radar_topics_[static_cast<std::size_t>(m.scan.sensor_id)], m.stamp_ns,
                            array_);
      break;
    }
    case Message::Kind::kOdometry:
      writer_->WriteMessage(odometry_topic_, m.stamp_ns,
                            sim::ToRosOdometry(m.odometry, "odom", "base_link", true));
      break;
    case Message::Kind::kGroundTruth:  // live sources have none
      return;
    case Message::Kind::kEvent: {
      rosbag::CdrWriter cdr(&cdr_);
      cdr.WriteString(m.text);
      writer_->Write(event_topic_, m.stamp_ns, cdr_);
      break;
    }
  }
  ++written_;
}

void Dispatcher::Dispatch(LiveMessage&& msg, bool restamp) {
  {
    std::lock_guard<std::mutex> lock(mutex_);
    // Stamped under the lock: stamp order = queue order = recording order.
    msg.arrival = SteadyClock::now();
    if (restamp) {
      msg.stamp_ns = clock_->Now();
      if (msg.kind == Message::Kind::kRadarScan) msg.scan.stamp_ns = msg.stamp_ns;
      if (msg.kind == Message::Kind::kOdometry) msg.odometry.stamp_ns = msg.stamp_ns;
    }
    if (recorder_ != nullptr) {
      recorder_->Push(msg);
    } else {
      held_.push_back(msg);
    }
    if (msg.kind != Message::Kind::kEvent && msg.for_slam) {
      if (queue_.size() >= capacity_) {
        queue_.pop_front();
        ++dropped_;
      }
      queue_.push_back(std::move(msg));
    }
  }
  wake_.notify_one();
}

void Dispatcher::AttachRecorder(Recorder* recorder) {
  std::lock_guard<std::mutex> lock(mutex_);
  recorder_ = recorder;
  for (const LiveMessage& m : held_) recorder_->Push(m);
  held_.clear();
}

void Dispatcher::Event(const std::string& text) {
  LiveMessage m;
  m.kind = Message::Kind::kEvent;
  m.text = text;
  Publish(std::move(m));
}

bool Dispatcher::Pop(LiveMessage* out, std::chrono::milliseconds timeout) {
  std::unique_lock<std::mutex> lock(mutex_);
  if (!wake_.wait_for(lock, timeout, [this] { return !queue_.empty(); })) return false;
  *out = std::move(queue_.front());
  queue_.pop_front();
  return true;
}

std::string DefaultRecordingName() {
  const std::time_t t = std::time(nullptr);
  std::tm tm{};
  ::localtime_r(&t, &tm);
  char buffer[64];
  std::strftime(buffer, sizeof(buffer), "rosbag2_%Y_%m_%d-%H_%M_%S", &tm);
  return buffer;
}

}  // namespace uwbsar::slam
