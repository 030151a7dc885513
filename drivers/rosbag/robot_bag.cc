#include "drivers/rosbag/robot_bag.h"

#include "core/errors.h"
#include "core/log.h"
#include "core/stamp_range.h"
#include "drivers/rosbag/bag_reader.h"
#include "drivers/rosbag/ros_codecs.h"

namespace uwbsar::rosbag {
namespace {

enum class Role { kNone, kRadar, kOdometry, kGroundTruth };

/// The message types the reader decodes; kOther topics are counted and skipped.
enum class MessageKind { kOther, kFloat32MultiArray, kOdometry, kLaserScan, kTf };

struct TopicPlan {
  MessageKind kind = MessageKind::kOther;
  Role role = Role::kNone;
  int sensor_id = -1;
};

MessageKind KindOf(const std::string& type) {
  if (type == kFloat32MultiArrayType) return MessageKind::kFloat32MultiArray;
  if (type == kOdometryType) return MessageKind::kOdometry;
  if (type == kLaserScanType) return MessageKind::kLaserScan;
  if (type == kTfMessageType) return MessageKind::kTf;
  return MessageKind::kOther;
}

void Expect(const BagInfo& info, const TopicInfo& t, const char* expected, const std::string& why) {
  if (t.type == expected) return;
  throw InputError(info.path + ": topic " + t.name + " has type " + t.type + ", but " + why +
                   " expects " + expected);
}

/// The kind of every topic of the bag, and the role the options give some of them.
std::vector<TopicPlan> PlanTopics(const BagReader& reader, const RobotBagOptions& options) {
  const BagInfo& info = reader.Info();
  std::vector<TopicPlan> plans(info.topics.size());
  for (std::size_t i = 0; i < info.topics.size(); ++i) plans[i].kind = KindOf(info.topics[i].type);
  for (std::size_t r = 0; r < options.radar_topics.size(); ++r) {
    const int i = reader.FindTopic(options.radar_topics[r]);
    if (i < 0) {
      Log(LogLevel::kWarning, info.path + ": no radar topic " + options.radar_topics[r]);
      continue;
    }
    const std::string radar = r < options.radar_names.size() && !options.radar_names[r].empty()
                                  ? options.radar_names[r]
                                  : std::to_string(r);
    Expect(info, info.topics[static_cast<std::size_t>(i)], kFloat32MultiArrayType,
           "radars[" + radar + "].topic");
    plans[static_cast<std::size_t>(i)].role = Role::kRadar;
    plans[static_cast<std::size_t>(i)].sensor_id = static_cast<int>(r);
  }
  const std::pair<const std::string*, Role> odom_topics[] = {
      {&options.odometry_topic, Role::kOdometry},
      {&options.ground_truth_topic, Role::kGroundTruth}};
  for (const auto& [name, role] : odom_topics) {
    if (name->empty()) continue;
    const int i = reader.FindTopic(*name);
    if (i < 0) {
      if (role == Role::kOdometry) {
        Log(LogLevel::kWarning, info.path + ": no odometry topic " + *name);
      }
      continue;
    }
    Expect(info, info.topics[static_cast<std::size_t>(i)], kOdometryType,
           role == Role::kOdometry ? "the odometry topic" : "the ground-truth topic");
    plans[static_cast<std::size_t>(i)].role = role;
  }
  return plans;
}

/// Decodes messages by their topic's plan and hands them to the visitor, counting
/// them; the decode buffers are reused from message to message.
class MessageDispatcher {
 public:
  MessageDispatcher(const RobotBagOptions& options, RobotBagVisitor& visitor, RobotBagStats* stats)
      : options_(options), visitor_(visitor), stats_(*stats) {}

  void Dispatch(const BagMessage& m, const TopicPlan& plan, const MessageContext& ctx) {
    switch (plan.kind) {
      case MessageKind::kFloat32MultiArray:
        OnFloat32MultiArray(m, plan, ctx);
        break;
      case MessageKind::kOdometry:
        OnOdometry(m, plan, ctx);
        break;
      case MessageKind::kLaserScan:
        DecodeCdr(m.data, m.size, &scan_);
        visitor_.OnLaserScan(ctx, scan_);
        ++stats_.laser_scans;
        break;
      case MessageKind::kTf:
        DecodeCdr(m.data, m.size, &tf_);
        visitor_.OnTf(ctx, tf_);
        ++stats_.tf;
        break;
      case MessageKind::kOther:
        ++stats_.skipped;
        ++stats_.skipped_by_type[ctx.type];
        break;
    }
  }

 private:
  void OnFloat32MultiArray(const BagMessage& m, const TopicPlan& plan, const MessageContext& ctx) {
    DecodeCdr(m.data, m.size, &f32_);
    visitor_.OnFloat32MultiArray(ctx, f32_);
    if (plan.role != Role::kRadar) return;
    radar_.stamp_ns = m.log_time_ns;
    radar_.sensor_id = plan.sensor_id;
    radar_.samples.swap(f32_.data);  // no copy; swapped back below
    visitor_.OnRadarScan(radar_);
    radar_.samples.swap(f32_.data);
    ++stats_.radar_scans;
  }

  void OnOdometry(const BagMessage& m, const TopicPlan& plan, const MessageContext& ctx) {
    DecodeCdr(m.data, m.size, &odom_);
    visitor_.OnOdometryMessage(ctx, odom_);
    const TimestampNs header_ns =
        static_cast<TimestampNs>(odom_.header.stamp.sec) * 1000000000 + odom_.header.stamp.nanosec;
    const TimestampNs stamp =
        options_.odometry_header_stamp && header_ns != 0 ? header_ns : m.log_time_ns;
    if (plan.role != Role::kNone && !IsOutputStamp(stamp)) {
      throw InputError("header " + StampOutsideOutputRange(stamp));
    }
    if (plan.role == Role::kOdometry) {
      visitor_.OnOdometry(ToOdometrySample(odom_, stamp));
      ++stats_.odometry;
    } else if (plan.role == Role::kGroundTruth) {
      visitor_.OnGroundTruth(ToOdometrySample(odom_, stamp));
      ++stats_.ground_truth;
    }
  }

  const RobotBagOptions& options_;
  RobotBagVisitor& visitor_;
  RobotBagStats& stats_;
  Float32MultiArray f32_;
  Odometry odom_;
  LaserScan scan_;
  TfMessage tf_;
  RadarScan radar_;
};

}  // namespace

RobotBagOptions RobotBagOptionsFor(const std::vector<RadarConfig>& radars,
                                   const std::string& odometry_topic,
                                   const std::string& ground_truth_topic) {
  RobotBagOptions options;
  options.radar_topics.clear();
  options.radar_names.clear();
  for (const RadarConfig& r : radars) {
    options.radar_topics.push_back(r.topic);
    options.radar_names.push_back(r.name);
  }
  options.odometry_topic = odometry_topic;
  options.ground_truth_topic = ground_truth_topic;
  return options;
}

OdometrySample ToOdometrySample(const Odometry& msg, TimestampNs stamp_ns) {
  OdometrySample s;
  s.stamp_ns = stamp_ns;
  s.T_world_robot.x_m = msg.position.x;
  s.T_world_robot.y_m = msg.position.y;
  s.T_world_robot.yaw_rad = YawFromQuaternion(msg.orientation);
  s.linear_velocity_mps = msg.linear.x;
  s.angular_velocity_radps = msg.angular.z;
  return s;
}

RobotBagStats ReadRobotBag(const std::string& path, const RobotBagOptions& options,
                           RobotBagVisitor& visitor) {
  BagReader reader(path);
  return ReadRobotBag(reader, options, visitor);
}

RobotBagStats ReadRobotBag(BagReader& reader, const RobotBagOptions& options,
                           RobotBagVisitor& visitor) {
  const BagInfo& info = reader.Info();
  const std::vector<TopicPlan> plans = PlanTopics(reader, options);
  RobotBagStats stats;
  MessageDispatcher dispatcher(options, visitor, &stats);
  BagMessage m;
  while (reader.Next(&m)) {
    ++stats.messages;
    const TopicInfo& topic = info.topics[static_cast<std::size_t>(m.topic)];
    const MessageContext ctx{topic.name, topic.type, m.log_time_ns};
    const TopicPlan& plan = plans[static_cast<std::size_t>(m.topic)];
    // The stamps uwbsar uses go into its outputs, which cannot hold every stamp a bag can.
    if (plan.role != Role::kNone && !IsOutputStamp(m.log_time_ns)) {
      throw InputError(info.files[static_cast<std::size_t>(m.file)] + ": message " +
                       std::to_string(stats.messages - 1) + " on " + topic.name + " (" +
                       topic.type + "): log time " + StampOutsideOutputRange(m.log_time_ns));
    }
    try {
      dispatcher.Dispatch(m, plan, ctx);
    } catch (const InputError& e) {
      throw InputError(info.files[static_cast<std::size_t>(m.file)] + ": message at " +
                       std::to_string(m.log_time_ns) + " ns on " + topic.name + " (" + topic.type +
                       "): " + e.what());
    }
  }
  return stats;
}

RobotLog LoadRobotBag(const std::string& path, const RobotBagOptions& options) {
  struct Collector : RobotBagVisitor {
    RobotLog log;
    void OnRadarScan(const RadarScan& s) override { log.scans.push_back(s); }
    void OnOdometry(const OdometrySample& o) override { log.odometry.push_back(o); }
    void OnGroundTruth(const OdometrySample& o) override { log.ground_truth.push_back(o); }
  } collector;
  collector.log.stats = ReadRobotBag(path, options, collector);
  return std::move(collector.log);
}

}  // namespace uwbsar::rosbag
