// Subscribes to the robot's ROS 2 radar (std_msgs/Float32MultiArray) and wheel
// odometry (nav_msgs/Odometry) topics over DDS and hands decoded samples to
// callbacks, on one thread of its own (a DDS waitset), in arrival order per topic.
// Publishers leaving and returning, silent topics, duplicate/out-of-order stamps,
// wrong types on our topic names and unusable samples are reported as DdsEvents;
// malformed bytes are dropped by DDS before they reach us, so they never crash.
#pragma once

#include <dds/dds.h>

#include <atomic>
#include <chrono>
#include <cstdint>
#include <functional>
#include <memory>
#include <mutex>
#include <string>
#include <thread>
#include <vector>

#include "core/types.h"
#include "drivers/dds/dds_config.h"
#include "drivers/dds/dds_events.h"
#include "drivers/dds/participant.h"
#include "drivers/dds/publication_monitor.h"

namespace uwbsar::dds {

/// One radar scan. Float32MultiArray has no header: scan.stamp_ns is the DDS source
/// timestamp (the publisher's clock when it wrote the sample).
struct RadarMessage {
  RadarScan scan;                ///< sensor_id = index of the topic in radar_topics
  TimestampNs reception_ns = 0;  ///< local wall clock when taken
  bool in_order = true;          ///< false: source stamp not after the previous one of this sensor
};

/// One odometry sample. sample.stamp_ns is the header stamp.
struct OdometryMessage {
  OdometrySample sample;
  TimestampNs source_stamp_ns = 0;  ///< DDS source timestamp
  TimestampNs reception_ns = 0;     ///< local wall clock when taken
  std::string frame_id;
  std::string child_frame_id;
  /// false: header stamp equal to (duplicate) or before (out of order) the latest
  /// in-order one; callers skip it for SLAM but may still record it.
  bool in_order = true;
};

struct Ros2SubscriberStats {
  std::uint64_t radar_samples = 0;               ///< delivered to on_radar (in order or not)
  std::uint64_t odometry_samples = 0;            ///< delivered to on_odometry (in order or not)
  std::uint64_t events[kNumDdsEventKinds] = {};  ///< per DdsEventKind
  std::uint64_t callback_exceptions = 0;         ///< callbacks that threw (caught, counted)
};

class Ros2Subscriber {
 public:
  struct Callbacks {
    std::function<void(RadarMessage&&)> on_radar;
    std::function<void(OdometryMessage&&)> on_odometry;
    std::function<void(const DdsEvent&)> on_event;
  };

  /// Subscribes with the QoS of `config` (reliability, history_depth; XCDR1) to
  /// `radar_topics[i]` (sensor i) and `odometry_topic` (ROS 2 names, e.g. "/odom";
  /// "" = none) and starts the thread. Throws InputError for a bad or repeated topic
  /// name or QoS setting, DdsError when DDS refuses. `participant` must outlive this object.
  Ros2Subscriber(Participant& participant, const DdsConfig& config,
                 const std::vector<std::string>& radar_topics, const std::string& odometry_topic,
                 Callbacks callbacks);
  /// Stops the thread; no callback runs after it returns.
  ~Ros2Subscriber();
  Ros2Subscriber(const Ros2Subscriber&) = delete;
  Ros2Subscriber& operator=(const Ros2Subscriber&) = delete;

  /// Stops the thread and deletes the readers (idempotent).
  void Stop();
  Ros2SubscriberStats Stats() const;
  /// Publishers currently matched on a ROS 2 topic we subscribe to (0 if unknown).
  int MatchedPublishers(const std::string& ros_topic) const;

 private:
  struct Topic;
  void Run();
  void TakeRadar(Topic& topic);
  void TakeOdometry(Topic& topic);
  void HandleStatus(Topic& topic);
  void CheckSilence(Topic& topic, std::chrono::steady_clock::time_point now);
  void NoteActivity(Topic& topic);
  template <class Message>
  void Deliver(const std::function<void(Message&&)>& callback, Message&& message,
               std::uint64_t Ros2SubscriberStats::*counter);
  void Emit(DdsEventKind kind, const std::string& topic, const std::string& detail);

  Callbacks callbacks_;
  double silence_timeout_s_;
  std::vector<std::unique_ptr<Topic>> topics_;
  dds_entity_t waitset_ = 0;
  dds_entity_t stop_guard_ = 0;
  std::vector<dds_entity_t> entities_;  // readers, topics, conditions: deleted by Stop()
  std::unique_ptr<PublicationMonitor> monitor_;
  mutable std::mutex stats_mutex_;
  Ros2SubscriberStats stats_;
  std::thread thread_;
  std::atomic<bool> stopped_{false};
};

}  // namespace uwbsar::dds
