// Conversions between the generated ROS 2 DDS types and uwbsar's types: stamps,
// planar poses, odometry, and the occupancy grid's row order.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "core/pose2.h"
#include "core/types.h"
#include "drivers/dds/ros2_types.h"
#include "imaging/occupancy_grid.h"

namespace uwbsar::dds {

TimestampNs StampToNs(const builtin_interfaces_msg_dds__Time_& stamp);
/// The ROS time of `t` (nanosec in [0, 1e9) also for times before the epoch).
builtin_interfaces_msg_dds__Time_ NsToStamp(TimestampNs t);

/// Yaw about +z of a quaternion (need not be unit length, must not be zero).
double YawFromQuaternion(double x, double y, double z, double w);
/// The planar pose as a 3-D pose: z = 0, rotation by yaw about +z.
geometry_msgs_msg_dds__Pose_ PoseToDds(const Pose2& pose);

/// Odometry as the SLAM layer takes it: stamp from the header, position x/y, yaw from
/// the orientation, forward (twist linear.x) and yaw-rate (twist angular.z) velocities.
/// False with `why` set when a value is not finite or the quaternion is zero.
bool OdometryFromDds(const nav_msgs_msg_dds__Odometry_& msg, OdometrySample* out, std::string* why);

}  // namespace uwbsar::dds
