// The C types idlc generates from drivers/dds/idl/*.idl (ROS 2 messages in the
// rosidl DDS mapping), and their DDS type names, in one place.
#pragma once

#include "builtin_interfaces.h"
#include "geometry_msgs.h"
#include "nav_msgs.h"
#include "sensor_msgs.h"
#include "std_msgs.h"
#include "tf2_msgs.h"
#include "visualization_msgs.h"

namespace uwbsar::dds {

inline constexpr const char* kFloat32MultiArrayTypeName = "std_msgs::msg::dds_::Float32MultiArray_";
inline constexpr const char* kOdometryTypeName = "nav_msgs::msg::dds_::Odometry_";
inline constexpr const char* kOccupancyGridTypeName = "nav_msgs::msg::dds_::OccupancyGrid_";
inline constexpr const char* kPathTypeName = "nav_msgs::msg::dds_::Path_";
inline constexpr const char* kPoseStampedTypeName = "geometry_msgs::msg::dds_::PoseStamped_";
inline constexpr const char* kMarkerArrayTypeName = "visualization_msgs::msg::dds_::MarkerArray_";

/// visualization_msgs/Marker constants used here.
inline constexpr int kMarkerLineList = 5;
inline constexpr int kMarkerAdd = 0;
inline constexpr int kMarkerDeleteAll = 3;

}  // namespace uwbsar::dds
