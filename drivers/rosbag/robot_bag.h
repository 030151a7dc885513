// From a ROS 2 bag to the project's messages: each message is decoded by its topic's
// type string (Float32MultiArray, Odometry, LaserScan, TFMessage); radar topics named
// in the configuration become RadarScan (sensor_id = index of the radar), the
// configured odometry topic becomes OdometrySample (yaw from the quaternion). Topics
// of other types are skipped and counted. A configured topic whose type is not the
// expected one is an InputError naming the bag, the topic and both types.
#pragma once

#include <cstdint>
#include <map>
#include <string>
#include <vector>

#include "core/radar_config.h"
#include "core/types.h"
#include "drivers/rosbag/bag_reader.h"
#include "drivers/rosbag/ros_messages.h"

namespace uwbsar::rosbag {

struct RobotBagOptions {
  /// Radar scan topics; sensor_id = index (Config::radars[i].topic).
  std::vector<std::string> radar_topics = {"/UWBradar0/readings", "/UWBradar1/readings"};
  /// Their radars' names (Config::radars[i].name), for messages: radars[left].topic. A topic
  /// without a name is named by its index.
  std::vector<std::string> radar_names = {"left", "right"};
  std::string odometry_topic = "/odom";                   ///< wheel odometry
  std::string ground_truth_topic = "/ground_truth/odom";  ///< optional (simulated runs)
  /// Stamp odometry with its header stamp instead of the receive time. Off by default:
  /// radar scans (Float32MultiArray) carry no header, so receive time keeps one clock.
  bool odometry_header_stamp = false;
};

/// Every topic from the configuration (radars[i].topic, slam.odometry_topic,
/// slam.ground_truth_topic): the one place that maps configuration to bag topics, used
/// by every command that reads bags (map, detectors, info --decode).
RobotBagOptions RobotBagOptionsFor(const std::vector<RadarConfig>& radars,
                                   const std::string& odometry_topic,
                                   const std::string& ground_truth_topic);
/// The same from any configuration holding radars[] and slam.*.
template <class Config>
RobotBagOptions RobotBagOptionsFromConfig(const Config& config) {
  return RobotBagOptionsFor(config.radars, config.slam.odometry_topic,
                            config.slam.ground_truth_topic);
}

struct MessageContext {
  const std::string& topic;
  const std::string& type;
  TimestampNs log_time_ns;
};

/// Receives decoded messages in receive-time order. Override what you need.
class RobotBagVisitor {
 public:
  virtual ~RobotBagVisitor() = default;
  virtual void OnRadarScan(const RadarScan& /*scan*/) {}
  virtual void OnOdometry(const OdometrySample& /*odometry*/) {}
  virtual void OnGroundTruth(const OdometrySample& /*pose*/) {}
  /// Every message of the four types, radar and odometry topics included.
  virtual void OnFloat32MultiArray(const MessageContext&, const Float32MultiArray&) {}
  virtual void OnOdometryMessage(const MessageContext&, const Odometry&) {}
  virtual void OnLaserScan(const MessageContext&, const LaserScan&) {}
  virtual void OnTf(const MessageContext&, const TfMessage&) {}
};

struct RobotBagStats {
  std::uint64_t messages = 0;
  std::uint64_t radar_scans = 0;
  std::uint64_t odometry = 0;
  std::uint64_t ground_truth = 0;
  std::uint64_t laser_scans = 0;
  std::uint64_t tf = 0;
  std::uint64_t skipped = 0;                             ///< messages of other types
  std::map<std::string, std::uint64_t> skipped_by_type;  ///< type -> count
};

/// Streams a bag (directory or .db3/.mcap) through `visitor`. Throws InputError on bad
/// input, naming the file, the topic and the message time.
RobotBagStats ReadRobotBag(const std::string& path, const RobotBagOptions& options,
                           RobotBagVisitor& visitor);
/// The same from an open reader (read once: a file-compressed bag is decompressed once).
RobotBagStats ReadRobotBag(BagReader& reader, const RobotBagOptions& options,
                           RobotBagVisitor& visitor);

/// Everything the SLAM pipeline needs from a bag, in memory (like TextLog).
struct RobotLog {
  std::vector<RadarScan> scans;
  std::vector<OdometrySample> odometry;
  std::vector<OdometrySample> ground_truth;
  RobotBagStats stats;
};
RobotLog LoadRobotBag(const std::string& path, const RobotBagOptions& options);

/// The robot pose and twist of an Odometry message (planar: x, y, yaw).
OdometrySample ToOdometrySample(const Odometry& msg, TimestampNs stamp_ns);

}  // namespace uwbsar::rosbag
