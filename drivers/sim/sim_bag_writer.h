// Writes a SimStream as a ROS 2 bag like the real robot records it, plus the
// ground truth as a TUM trajectory:
//   radars[i].topic               std_msgs/msg/Float32MultiArray  (scan samples, empty layout)
//   simulator.odometry.topic      nav_msgs/msg/Odometry  (wheel odometry, odom -> base_link)
//   .ground_truth_topic           nav_msgs/msg/Odometry  (true pose, map -> base_link)
//   simulator.laser.topic         sensor_msgs/msg/LaserScan (if enabled; frame base_scan)
// Receive time (the bag timestamp) = header stamp = simulated time. The bag is
// written message by message, so memory stays small whatever the run's length.
#pragma once

#include <functional>
#include <string>

#include "drivers/rosbag/ros_messages.h"
#include "drivers/sim/sim_stream.h"

namespace uwbsar::sim {

struct SimBagSummary {
  long long radar_scans = 0;
  long long odometry = 0;
  long long ground_truth = 0;
  long long laser_scans = 0;
  OdometrySample last_odometry;  ///< for drift reports
  OdometrySample last_ground_truth;
};

/// Drains `stream` into a bag at `bag_dir` (storage "sqlite3" or "mcap") and the ground
/// truth into `tum_path` (empty: not written). Throws InputError if the bag exists or
/// cannot be written.
/// `on_message` (optional) is called with each message's stamp once it is written (progress).
SimBagSummary WriteSimBag(SimStream* stream, const SimSettings& config, const std::string& bag_dir,
                          const std::string& storage, const std::string& tum_path,
                          const std::function<void(TimestampNs)>& on_message = nullptr);

/// The ROS messages of one simulated message (exposed for tests).
rosbag::Odometry ToRosOdometry(const OdometrySample& pose, const std::string& frame_id,
                               const std::string& child_frame_id, bool with_covariance);
rosbag::LaserScan ToRosLaserScan(const SimLaserScan& scan);

}  // namespace uwbsar::sim
