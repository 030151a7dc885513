#include "drivers/rosbag/robot_bag.h"

#include "drivers/rosbag/bag_reader.h"
#include "drivers/rosbag/ros_codecs.h"
#include "slam/errors.h"
#include "slam/log.h"

namespace uwbsar::rosbag {
namespace {

enum class Role { kNone, kRadar, kOdometry, kGroundTruth };

struct TopicPlan {
  int kind = -1;  // 0 Float32MultiArray, 1 Odometry, 2 LaserScan, 3 TFMessage, -1 other
  Role role = Role::kNone;
  int sensor_id = -1;
};

int KindOf(const std::string& type) {
  if (type == kFloat32MultiArrayType) return 0;
  if (type == kOdometryType) return 1;
  if (type == kLaserScanType) return 2;
  if (type == kTfMessageType) return 3;
  return -1;
}

void Expect(const BagInfo& info, const TopicInfo& t, const char* expected, const std::string& why) {
  if (t.type == expected) return;
  throw InputError(info.path + ": topic " + t.name + " has type " + t.type + ", but " + why +
                   " expects " + expected);
}

}  // namespace

RobotBagOptions RobotBagOptionsFromConfig(const Config& config) {
  RobotBagOptions options;
  options.radar_topics.clear();
  for (const RadarConfig& r : config.radars) options.radar_topics.push_back(r.topic);
  options.odometry_topic = config.slam.odometry_topic;
  options.ground_truth_topic = config.slam.ground_truth_topic;
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
  const std::string& path = info.path;
  std::vector<TopicPlan> plans(info.topics.size());
  for (std::size_t i = 0; i < info.topics.size(); ++i) plans[i].kind = KindOf(info.topics[i].type);
  for (std::size_t r = 0; r < options.radar_topics.size(); ++r) {
    const int i = reader.FindTopic(options.radar_topics[r]);
    if (i < 0) {
      Log(LogLevel::kWarning, path + ": no radar topic " + options.radar_topics[r]);
      continue;
    }
    Expect(info, info.topics[static_cast<std::size_t>(i)], kFloat32MultiArrayType,
           "radars[" + std::to_string(r) + "].topic");
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
      if (role == Role::kOdometry) Log(LogLevel::kWarning, path + ": no odometry topic " + *name);
      continue;
    }
    Expect(info, info.topics[static_cast<std::size_t>(i)], kOdometryType,
           role == Role::kOdometry ? "the odometry topic" : "the ground-truth topic");
    plans[static_cast<std::size_t>(i)].role = role;
  }

  RobotBagStats stats;
  Float32MultiArray f32;
  Odometry odom;
  LaserScan scan;
  TfMessage tf;
  RadarScan radar;
  BagMessage m;
  while (reader.Next(&m)) {
    ++stats.messages;
    const TopicInfo& topic = info.topics[static_cast<std::size_t>(m.topic)];
    const TopicPlan& plan = plans[static_cast<std::size_t>(m.topic)];
    const MessageContext ctx{topic.name, topic.type, m.log_time_ns};
    try {
      switch (plan.kind) {
        case 0:
          DecodeCdr(m.data, m.size, &f32);
          visitor.OnFloat32MultiArray(ctx, f32);
          if (plan.role == Role::kRadar) {
            radar.stamp_ns = m.log_time_ns;
            radar.sensor_id = plan.sensor_id;
            radar.samples.swap(f32.data);  // no copy; swapped back below
            visitor.OnRadarScan(radar);
            radar.samples.swap(f32.data);
            ++stats.radar_scans;
          }
          break;
        case 1: {
          DecodeCdr(m.data, m.size, &odom);
          visitor.OnOdometryMessage(ctx, odom);
          const TimestampNs header_ns =
              static_cast<TimestampNs>(odom.header.stamp.sec) * 1000000000 +
              odom.header.stamp.nanosec;
          const TimestampNs stamp =
              options.odometry_header_stamp && header_ns != 0 ? header_ns : m.log_time_ns;
          if (plan.role == Role::kOdometry) {
            visitor.OnOdometry(ToOdometrySample(odom, stamp));
            ++stats.odometry;
          } else if (plan.role == Role::kGroundTruth) {
            visitor.OnGroundTruth(ToOdometrySample(odom, stamp));
            ++stats.ground_truth;
          }
          break;
        }
        case 2:
          DecodeCdr(m.data, m.size, &scan);
          visitor.OnLaserScan(ctx, scan);
          ++stats.laser_scans;
          break;
        case 3:
          DecodeCdr(m.data, m.size, &tf);
          visitor.OnTf(ctx, tf);
          ++stats.tf;
          break;
        default:
          ++stats.skipped;
          ++stats.skipped_by_type[topic.type];
      }
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
