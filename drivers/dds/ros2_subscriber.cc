#include "drivers/dds/ros2_subscriber.h"

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <functional>
#include <map>
#include <utility>

#include "core/errors.h"
#include "drivers/dds/dds_check.h"
#include "drivers/dds/ros2_convert.h"
#include "drivers/dds/ros2_qos.h"
#include "drivers/dds/ros2_types.h"

namespace uwbsar::dds {
namespace {

constexpr dds_attach_t kStopAttach = -1;
constexpr dds_attach_t kMonitorAttach = -2;
constexpr int kTakeBatch = 32;

std::string PolicyName(dds_qos_policy_id_t id) {
  switch (id) {
    case DDS_RELIABILITY_QOS_POLICY_ID:
      return "reliability";
    case DDS_DURABILITY_QOS_POLICY_ID:
      return "durability";
    case DDS_DEADLINE_QOS_POLICY_ID:
      return "deadline";
    case DDS_LIVELINESS_QOS_POLICY_ID:
      return "liveliness";
    case DDS_OWNERSHIP_QOS_POLICY_ID:
      return "ownership";
    case DDS_DATA_REPRESENTATION_QOS_POLICY_ID:
      return "data representation";
    default:
      return "policy " + std::to_string(static_cast<int>(id));
  }
}

std::string Seconds(double s) {
  char buf[32];
  std::snprintf(buf, sizeof(buf), "%.1f s", s);
  return buf;
}

// Stamps must increase; an equal stamp is a duplicate, an earlier one out of order.
// Reports it and returns false without moving the latest in-order stamp.
bool CheckOrder(bool* has_last, TimestampNs* last, TimestampNs stamp,
                const std::function<void(DdsEventKind, const std::string&)>& report) {
  if (*has_last && stamp <= *last) {
    const bool duplicate = stamp == *last;
    report(duplicate ? DdsEventKind::kDuplicate : DdsEventKind::kOutOfOrder,
           std::string(duplicate ? "duplicate" : "out-of-order") + " stamp " +
               std::to_string(stamp) + " ns after " + std::to_string(*last) + " ns");
    return false;
  }
  *has_last = true;
  *last = stamp;
  return true;
}

}  // namespace

struct Ros2Subscriber::Topic {
  enum class Kind { kRadar, kOdometry };
  Kind kind = Kind::kRadar;
  int sensor_index = 0;
  std::string ros_name;
  dds_entity_t reader = 0;
  std::atomic<int> matched{0};
  bool was_gone = false;
  bool silent = false;
  std::chrono::steady_clock::time_point last_activity;  // last sample, or the match
  bool has_last_stamp = false;
  TimestampNs last_stamp_ns = 0;  // latest in-order stamp (header, or source for radar)
};

Ros2Subscriber::Ros2Subscriber(Participant& participant, const DdsConfig& config,
                               const std::vector<std::string>& radar_topics,
                               const std::string& odometry_topic, Callbacks callbacks)
    : callbacks_(std::move(callbacks)), silence_timeout_s_(config.silence_timeout_s) {
  const dds_entity_t pp = participant.handle();
  Qos qos;
  SetRos2Qos(qos.get(), config.reliability, config.history_depth, Durability::kVolatile);
  std::map<std::string, std::string> expected_types;
  try {
    waitset_ = Check(dds_create_waitset(pp), "dds_create_waitset");
    entities_.push_back(waitset_);
    stop_guard_ = Check(dds_create_guardcondition(pp), "dds_create_guardcondition");
    entities_.push_back(stop_guard_);
    Check(dds_waitset_attach(waitset_, stop_guard_, kStopAttach), "dds_waitset_attach(guard)");

    auto add = [&](Topic::Kind kind, int sensor_index, const std::string& ros_name) {
      for (const auto& other : topics_) {
        if (other->ros_name == ros_name) {
          throw InputError("ROS topic " + ros_name + " is subscribed twice (radar and " +
                           "odometry topics must all differ)");
        }
      }
      auto topic = std::make_unique<Topic>();
      topic->kind = kind;
      topic->sensor_index = sensor_index;
      topic->ros_name = ros_name;
      const std::string dds_name = RosTopicToDds(ros_name);
      const dds_topic_descriptor_t* desc = kind == Topic::Kind::kRadar
                                               ? &std_msgs_msg_dds__Float32MultiArray__desc
                                               : &nav_msgs_msg_dds__Odometry__desc;
      expected_types[dds_name] = desc->m_typename;
      const dds_entity_t dds_topic =
          Check(dds_create_topic(pp, desc, dds_name.c_str(), nullptr, nullptr),
                ("dds_create_topic(" + dds_name + ")").c_str());
      entities_.push_back(dds_topic);
      topic->reader = Check(dds_create_reader(pp, dds_topic, qos.get(), nullptr),
                            ("dds_create_reader(" + dds_name + ")").c_str());
      entities_.push_back(topic->reader);
      Check(dds_set_status_mask(topic->reader, DDS_SUBSCRIPTION_MATCHED_STATUS |
                                                   DDS_REQUESTED_INCOMPATIBLE_QOS_STATUS |
                                                   DDS_SAMPLE_LOST_STATUS),
            "dds_set_status_mask");
      const dds_entity_t cond =
          Check(dds_create_readcondition(topic->reader, DDS_ANY_STATE), "dds_create_readcondition");
      const auto index = static_cast<dds_attach_t>(topics_.size());
      Check(dds_waitset_attach(waitset_, cond, 2 * index), "dds_waitset_attach(data)");
      Check(dds_waitset_attach(waitset_, topic->reader, 2 * index + 1),
            "dds_waitset_attach(status)");
      topics_.push_back(std::move(topic));
    };
    for (std::size_t i = 0; i < radar_topics.size(); ++i) {
      add(Topic::Kind::kRadar, static_cast<int>(i), radar_topics[i]);
    }
    if (!odometry_topic.empty()) add(Topic::Kind::kOdometry, 0, odometry_topic);

    monitor_ = std::make_unique<PublicationMonitor>(pp, expected_types);
    entities_.push_back(monitor_->reader());
    const dds_entity_t monitor_cond = Check(
        dds_create_readcondition(monitor_->reader(), DDS_ANY_STATE), "dds_create_readcondition");
    Check(dds_waitset_attach(waitset_, monitor_cond, kMonitorAttach),
          "dds_waitset_attach(monitor)");
  } catch (...) {
    for (auto it = entities_.rbegin(); it != entities_.rend(); ++it) dds_delete(*it);
    throw;
  }
  thread_ = std::thread([this] { Run(); });
}

Ros2Subscriber::~Ros2Subscriber() { Stop(); }

void Ros2Subscriber::Stop() {
  if (stopped_.exchange(true)) return;
  dds_set_guardcondition(stop_guard_, true);
  if (thread_.joinable()) thread_.join();
  for (auto it = entities_.rbegin(); it != entities_.rend(); ++it) dds_delete(*it);
  entities_.clear();
}

Ros2SubscriberStats Ros2Subscriber::Stats() const {
  std::lock_guard<std::mutex> lock(stats_mutex_);
  return stats_;
}

int Ros2Subscriber::MatchedPublishers(const std::string& ros_topic) const {
  for (const auto& topic : topics_) {
    if (topic->ros_name == ros_topic) return topic->matched.load();
  }
  return 0;
}

void Ros2Subscriber::Emit(DdsEventKind kind, const std::string& topic, const std::string& detail) {
  {
    std::lock_guard<std::mutex> lock(stats_mutex_);
    ++stats_.events[static_cast<int>(kind)];
  }
  if (!callbacks_.on_event) return;
  try {
    callbacks_.on_event(DdsEvent{kind, topic, detail});
  } catch (...) {
    std::lock_guard<std::mutex> lock(stats_mutex_);
    ++stats_.callback_exceptions;
  }
}

void Ros2Subscriber::Run() {
  const dds_duration_t poll =
      silence_timeout_s_ > 0.0
          ? std::min<dds_duration_t>(DDS_MSECS(100),
                                     static_cast<dds_duration_t>(silence_timeout_s_ * 0.25e9))
          : DDS_MSECS(500);
  std::vector<dds_attach_t> triggered(2 * topics_.size() + 2);
  for (;;) {
    const dds_return_t n = dds_waitset_wait(waitset_, triggered.data(), triggered.size(), poll);
    if (n < 0) break;  // the waitset is gone: nothing more can arrive
    bool stop = false;
    for (dds_return_t i = 0; i < n; ++i) {
      const dds_attach_t a = triggered[static_cast<std::size_t>(i)];
      if (a == kStopAttach) {
        stop = true;
      } else if (a == kMonitorAttach) {
        for (const DdsEvent& e : monitor_->Poll()) Emit(e.kind, e.topic, e.detail);
      } else {
        Topic& topic = *topics_[static_cast<std::size_t>(a / 2)];
        if (a % 2 == 1) {
          HandleStatus(topic);
        } else if (topic.kind == Topic::Kind::kRadar) {
          TakeRadar(topic);
        } else {
          TakeOdometry(topic);
        }
      }
    }
    if (stop) break;
    const auto now = std::chrono::steady_clock::now();
    for (auto& topic : topics_) CheckSilence(*topic, now);
  }
}

void Ros2Subscriber::HandleStatus(Topic& topic) {
  dds_subscription_matched_status_t matched;
  if (dds_get_subscription_matched_status(topic.reader, &matched) == DDS_RETCODE_OK &&
      matched.current_count_change != 0) {
    const int before = topic.matched.exchange(static_cast<int>(matched.current_count));
    if (before == 0 && matched.current_count > 0) {
      topic.last_activity = std::chrono::steady_clock::now();
      topic.silent = false;
      if (topic.was_gone) {
        Emit(DdsEventKind::kPublisherBack, topic.ros_name,
             "publisher of " + topic.ros_name + " back");
      } else {
        Emit(DdsEventKind::kPublisherMatched, topic.ros_name,
             "publisher of " + topic.ros_name + " found");
      }
      topic.was_gone = false;
    } else if (before > 0 && matched.current_count == 0) {
      topic.was_gone = true;
      Emit(DdsEventKind::kPublisherGone, topic.ros_name,
           "publisher of " + topic.ros_name + " gone");
    }
  }
  dds_requested_incompatible_qos_status_t incompatible;
  if (dds_get_requested_incompatible_qos_status(topic.reader, &incompatible) == DDS_RETCODE_OK &&
      incompatible.total_count_change > 0) {
    Emit(DdsEventKind::kIncompatibleQos, topic.ros_name,
         "publisher of " + topic.ros_name + " offers an incompatible " +
             PolicyName(static_cast<dds_qos_policy_id_t>(incompatible.last_policy_id)) +
             " QoS (a best-effort publisher needs dds.reliability: best_effort)");
  }
  dds_sample_lost_status_t lost;
  if (dds_get_sample_lost_status(topic.reader, &lost) == DDS_RETCODE_OK &&
      lost.total_count_change > 0) {
    Emit(DdsEventKind::kSamplesLost, topic.ros_name,
         std::to_string(lost.total_count_change) + " samples of " + topic.ros_name + " lost");
  }
}

void Ros2Subscriber::CheckSilence(Topic& topic, std::chrono::steady_clock::time_point now) {
  if (silence_timeout_s_ <= 0.0 || topic.silent || topic.matched.load() == 0) return;
  const double idle_s = std::chrono::duration<double>(now - topic.last_activity).count();
  if (idle_s < silence_timeout_s_) return;
  topic.silent = true;
  Emit(DdsEventKind::kTopicSilent, topic.ros_name,
       "no sample on " + topic.ros_name + " for " + Seconds(silence_timeout_s_));
}

namespace {

/// Takes everything waiting on `reader` in loaned batches and calls `each(sample, info)` for
/// every sample that carries data (dispose/unregister notifications have none).
template <class Message, class Each>
void TakeAll(dds_entity_t reader, Each each) {
  void* samples[kTakeBatch];
  dds_sample_info_t infos[kTakeBatch];
  for (;;) {
    samples[0] = nullptr;
    const dds_return_t n = dds_take(reader, samples, infos, kTakeBatch, kTakeBatch);
    if (n <= 0) return;
    for (dds_return_t i = 0; i < n; ++i) {
      if (infos[i].valid_data) each(*static_cast<const Message*>(samples[i]), infos[i]);
    }
    dds_return_loan(reader, samples, n);
    if (n < kTakeBatch) return;
  }
}

}  // namespace

void Ros2Subscriber::TakeRadar(Topic& topic) {
  TakeAll<std_msgs_msg_dds__Float32MultiArray_>(
      topic.reader,
      [&](const std_msgs_msg_dds__Float32MultiArray_& msg, const dds_sample_info_t& info) {
        NoteActivity(topic);
        if (msg.data_._length == 0) {
          Emit(DdsEventKind::kInvalidSample, topic.ros_name,
               "empty radar scan on " + topic.ros_name);
          return;
        }
        RadarMessage out;
        out.scan.sensor_id = topic.sensor_index;
        out.scan.stamp_ns = info.source_timestamp;
        out.scan.samples.assign(msg.data_._buffer, msg.data_._buffer + msg.data_._length);
        out.reception_ns = dds_time();
        out.in_order = CheckOrder(&topic.has_last_stamp, &topic.last_stamp_ns, out.scan.stamp_ns,
                                  [&](DdsEventKind kind, const std::string& what) {
                                    Emit(kind, topic.ros_name, what + " on " + topic.ros_name);
                                  });
        Deliver(callbacks_.on_radar, std::move(out), &Ros2SubscriberStats::radar_samples);
      });
}

void Ros2Subscriber::TakeOdometry(Topic& topic) {
  TakeAll<nav_msgs_msg_dds__Odometry_>(
      topic.reader, [&](const nav_msgs_msg_dds__Odometry_& msg, const dds_sample_info_t& info) {
        NoteActivity(topic);
        OdometryMessage out;
        std::string why;
        if (!OdometryFromDds(msg, &out.sample, &why)) {
          Emit(DdsEventKind::kInvalidSample, topic.ros_name, why + " on " + topic.ros_name);
          return;
        }
        out.source_stamp_ns = info.source_timestamp;
        out.reception_ns = dds_time();
        if (msg.header_.frame_id_ != nullptr) out.frame_id = msg.header_.frame_id_;
        if (msg.child_frame_id_ != nullptr) out.child_frame_id = msg.child_frame_id_;
        out.in_order =
            CheckOrder(&topic.has_last_stamp, &topic.last_stamp_ns, out.sample.stamp_ns,
                       [&](DdsEventKind kind, const std::string& what) {
                         Emit(kind, topic.ros_name, "odometry " + what + " on " + topic.ros_name);
                       });
        Deliver(callbacks_.on_odometry, std::move(out), &Ros2SubscriberStats::odometry_samples);
      });
}

void Ros2Subscriber::NoteActivity(Topic& topic) {
  topic.last_activity = std::chrono::steady_clock::now();
  if (topic.silent) {
    topic.silent = false;
    Emit(DdsEventKind::kTopicResumed, topic.ros_name, "samples on " + topic.ros_name + " again");
  }
}

template <class Message>
void Ros2Subscriber::Deliver(const std::function<void(Message&&)>& callback, Message&& message,
                             std::uint64_t Ros2SubscriberStats::*counter) {
  {
    std::lock_guard<std::mutex> lock(stats_mutex_);
    ++(stats_.*counter);
  }
  if (!callback) return;
  try {
    callback(std::move(message));
  } catch (...) {
    std::lock_guard<std::mutex> lock(stats_mutex_);
    ++stats_.callback_exceptions;
  }
}

}  // namespace uwbsar::dds
