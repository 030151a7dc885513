// Publishes uwbsar's results as ROS 2 topics over DDS for RViz2: the map
// (nav_msgs/OccupancyGrid, latched like map_server's), the robot pose
// (geometry_msgs/PoseStamped), the optimised trajectory (nav_msgs/Path) and the
// accepted loop closures (visualization_msgs/MarkerArray: a DELETEALL, then one
// LINE_LIST), and the map -> odom transform on /tf. Everything is in the frame
// dds.map_frame. Thread-safe.
#pragma once

#include <dds/dds.h>

#include <mutex>
#include <string>
#include <utility>
#include <vector>

#include "core/pose2.h"
#include "core/types.h"
#include "drivers/dds/dds_config.h"
#include "drivers/dds/participant.h"
#include "imaging/occupancy_grid.h"

namespace uwbsar::dds {

/// One loop closure drawn as a line between the two keyframe positions.
using LoopSegment = std::pair<Point2, Point2>;

class Ros2Publisher {
 public:
  /// Creates the four writers: map reliable + transient local, keep-last 1; the others
  /// reliable, volatile, keep-last 10; all XCDR1. Throws InputError for a bad topic
  /// name, DdsError when DDS refuses. `participant` must outlive this object.
  Ros2Publisher(Participant& participant, const DdsConfig& config);
  ~Ros2Publisher();
  Ros2Publisher(const Ros2Publisher&) = delete;
  Ros2Publisher& operator=(const Ros2Publisher&) = delete;

  /// The grid with rows flipped to ROS order (bottom row first); origin = grid.origin.
  void PublishMap(const OccupancyGrid& grid, TimestampNs stamp);
  /// The robot pose in the map frame. At most one per dds.publish_pose_period_s of
  /// `stamp` time: returns false (nothing sent) for a pose that comes sooner, unless
  /// `final` (the run's last pose, after its last correction: always sent).
  bool PublishPose(TimestampNs stamp, const Pose2& T_map_robot, bool final = false);
  /// The trajectory: one PoseStamped per (stamp, pose), header stamp `stamp`.
  void PublishPath(TimestampNs stamp, const std::vector<std::pair<TimestampNs, Pose2>>& poses);
  /// DELETEALL, then one LINE_LIST marker (ns "loops", id 0) with two points per loop.
  void PublishLoops(TimestampNs stamp, const std::vector<LoopSegment>& segments);
  /// The map -> odometry frame correction on /tf (tf2_msgs/TFMessage), as a ROS 2 SLAM
  /// node publishes it, so RViz2 shows the robot's own frames in the map; no-op unless
  /// dds.publish_tf.
  void PublishMapToOdom(TimestampNs stamp, const Pose2& T_map_odom);

  /// Subscribers currently matched by the writer of `ros_topic` (0 if not ours).
  int MatchedSubscribers(const std::string& ros_topic) const;

 private:
  struct Writer {
    std::string ros_topic;
    dds_entity_t topic = 0;
    dds_entity_t writer = 0;
  };
  Writer Create(dds_entity_t participant, const dds_topic_descriptor_t* desc,
                const std::string& ros_topic, const dds_qos_t* qos);

  std::string frame_;
  double pose_period_s_;
  std::string odom_frame_;
  bool publish_tf_ = true;
  Writer map_, pose_, path_, loops_, tf_;
  std::mutex mutex_;
  bool has_last_pose_ = false;
  TimestampNs last_pose_ns_ = 0;
};

}  // namespace uwbsar::dds
