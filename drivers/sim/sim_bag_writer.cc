#include "drivers/sim/sim_bag_writer.h"

#include <cmath>
#include <fstream>

#include "core/errors.h"
#include "drivers/rosbag/bag_writer.h"
#include "drivers/rosbag/ros_codecs.h"
#include "drivers/sim/sim_recorder.h"

namespace uwbsar::sim {

rosbag::Odometry ToRosOdometry(const OdometrySample& pose, const std::string& frame_id,
                               const std::string& child_frame_id, bool with_covariance) {
  rosbag::Odometry msg;
  msg.header.stamp = rosbag::ToRosTime(pose.stamp_ns);
  msg.header.frame_id = frame_id;
  msg.child_frame_id = child_frame_id;
  msg.position = {pose.T_world_robot.x_m, pose.T_world_robot.y_m, 0.0};
  const double half = 0.5 * pose.T_world_robot.yaw_rad;
  msg.orientation = {0.0, 0.0, std::sin(half), std::cos(half)};
  msg.linear = {pose.linear_velocity_mps, 0.0, 0.0};
  msg.angular = {0.0, 0.0, pose.angular_velocity_radps};
  if (with_covariance) {
    // A planar base's usual covariance (as the Kobuki driver publishes): x, y and yaw
    // known, z, roll and pitch unobserved.
    const double pose_diag[6] = {0.1, 0.1, 1e6, 1e6, 1e6, 0.2};
    for (int i = 0; i < 6; ++i) {
      msg.pose_covariance[7 * i] = pose_diag[i];
      msg.twist_covariance[7 * i] = pose_diag[i];
    }
  }
  return msg;
}

rosbag::LaserScan ToRosLaserScan(const SimLaserScan& scan) {
  rosbag::LaserScan msg;
  msg.header.stamp = rosbag::ToRosTime(scan.stamp_ns);
  msg.header.frame_id = "base_scan";
  msg.angle_min = scan.angle_min_rad;
  msg.angle_increment = scan.angle_increment_rad;
  msg.angle_max =
      scan.angle_min_rad + scan.angle_increment_rad * static_cast<float>(scan.ranges_m.size() - 1);
  msg.scan_time = scan.scan_time_s;
  msg.range_min = scan.range_min_m;
  msg.range_max = scan.range_max_m;
  msg.ranges = scan.ranges_m;
  return msg;
}

SimBagSummary WriteSimBag(SimStream* stream, const SimSettings& config, const std::string& bag_dir,
                          const std::string& storage, const std::string& tum_path,
                          const std::function<void(TimestampNs)>& on_message) {
  rosbag::BagWriterOptions options;
  options.storage = storage;
  rosbag::BagWriter bag(bag_dir, options);
  std::vector<int> radar_topics;
  for (const RadarConfig& radar : config.radars) {
    radar_topics.push_back(bag.AddTopic(radar.topic, rosbag::kFloat32MultiArrayType));
  }
  const SimulatorConfig& s = config.simulator;
  const int odom_topic = bag.AddTopic(s.odometry.topic, rosbag::kOdometryType);
  const int truth_topic = bag.AddTopic(s.odometry.ground_truth_topic, rosbag::kOdometryType);
  const int laser_topic =
      s.laser.enabled ? bag.AddTopic(s.laser.topic, rosbag::kLaserScanType) : -1;
  SimBagSummary summary;
  std::vector<OdometrySample> ground_truth;
  rosbag::Float32MultiArray array;
  SimMessage msg;
  while (stream->Next(&msg)) {
    switch (msg.kind) {
      case SimMessage::Kind::kGroundTruth:
        bag.WriteMessage(truth_topic, msg.stamp_ns,
                         ToRosOdometry(msg.pose, "map", "base_link", false));
        ground_truth.push_back(msg.pose);
        summary.last_ground_truth = msg.pose;
        ++summary.ground_truth;
        break;
      case SimMessage::Kind::kOdometry:
        bag.WriteMessage(odom_topic, msg.stamp_ns,
                         ToRosOdometry(msg.pose, "odom", "base_link", true));
        summary.last_odometry = msg.pose;
        ++summary.odometry;
        break;
      case SimMessage::Kind::kRadarScan:
        array.data = std::move(msg.scan.samples);
        bag.WriteMessage(radar_topics.at(msg.scan.sensor_id), msg.stamp_ns, array);
        ++summary.radar_scans;
        break;
      case SimMessage::Kind::kLaserScan:
        bag.WriteMessage(laser_topic, msg.stamp_ns, ToRosLaserScan(msg.laser));
        ++summary.laser_scans;
        break;
    }
    if (on_message) on_message(msg.stamp_ns);
  }
  bag.Close();
  if (!tum_path.empty()) WriteTumTrajectory(tum_path, ground_truth);
  return summary;
}

}  // namespace uwbsar::sim
