// Configuration of the DDS link to a ROS 2 robot (`uwbsar run --source ros2`):
// uwbsar speaks DDS directly (Eclipse Cyclone DDS, ROS 2's rmw_cyclonedds wire
// format), so no ROS installation is needed. Radar and odometry topic names come
// from radars[i].topic and slam.odometry_topic; this struct holds the rest.
#pragma once

#include <string>

namespace uwbsar {

/// DDS participant, subscription QoS and the topics uwbsar publishes for RViz2.
struct DdsConfig {
  int domain_id = -1;  ///< DDS domain; -1 = $ROS_DOMAIN_ID, or 0 when unset (ROS 2's rule)
  std::string reliability = "reliable";     ///< radar/odometry subscriptions: reliable or
                                            ///< best_effort (must not exceed what the robot offers)
  int history_depth = 100;                  ///< keep-last depth of the subscriptions
  std::string network_interface = "";       ///< restrict DDS to this interface (e.g. eth0; "lo" =
                                            ///< loopback with unicast discovery); "" = Cyclone's
                                            ///< default or $CYCLONEDDS_URI
  std::string map_topic = "/uwbsar/map";    ///< nav_msgs/OccupancyGrid, latched (transient local)
  std::string pose_topic = "/uwbsar/pose";  ///< geometry_msgs/PoseStamped of the robot
  std::string path_topic = "/uwbsar/path";  ///< nav_msgs/Path of the optimised keyframes
  std::string loops_topic = "/uwbsar/loops";  ///< visualization_msgs/MarkerArray of accepted loops
  bool publish_in_serial_mode = false;        ///< with --source serial too, publish the results
                                              ///< (map, pose, path, loops, /tf) for RViz2
  bool publish_tf = true;                     ///< publish the map -> odom_frame correction on /tf
  std::string odom_frame = "odom";     ///< the robot's odometry frame (child of the /tf transform)
  std::string map_frame = "map";       ///< frame_id of everything uwbsar publishes
  double publish_pose_period_s = 0.1;  ///< at most one pose per this much sensor time (0 = all)
  double reorder_window_s = 0.1;       ///< radar and odometry samples are put back in stamp order
                                       ///< within this window before SLAM and the recording
  double startup_hold_s = 2.0;         ///< at the start, nothing is passed on until every topic
                                       ///< (radars, odometry) delivered a sample or this passed:
                                       ///< topics matched one by one still start in stamp order
  double silence_timeout_s = 1.0;      ///< a matched topic without samples this long is reported
                                       ///< as silent (0 = never)

  template <class V>
  void Visit(V& v) {
    v("domain_id", domain_id);
    v("reliability", reliability);
    v("history_depth", history_depth);
    v("network_interface", network_interface);
    v("map_topic", map_topic);
    v("pose_topic", pose_topic);
    v("path_topic", path_topic);
    v("loops_topic", loops_topic);
    v("publish_in_serial_mode", publish_in_serial_mode);
    v("publish_tf", publish_tf);
    v("odom_frame", odom_frame);
    v("map_frame", map_frame);
    v("publish_pose_period_s", publish_pose_period_s);
    v("reorder_window_s", reorder_window_s);
    v("startup_hold_s", startup_hold_s);
    v("silence_timeout_s", silence_timeout_s);
  }
};

/// Semantic checks of dds.* (ranges, names, consistency); throws ConfigError naming the
/// dotted key and `source_name`.
void Validate(const DdsConfig& config, const std::string& source_name);

}  // namespace uwbsar
