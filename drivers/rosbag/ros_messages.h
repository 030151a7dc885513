// The ROS 2 messages the project reads and writes, field for field as their .msg
// definitions (std_msgs, geometry_msgs, nav_msgs, sensor_msgs, tf2_msgs), so a
// decode/encode round trip loses nothing.
#pragma once

#include <array>
#include <cstdint>
#include <string>
#include <vector>

namespace uwbsar::rosbag {

struct RosTime {  // builtin_interfaces/msg/Time
  std::int32_t sec = 0;
  std::uint32_t nanosec = 0;
};

struct RosHeader {  // std_msgs/msg/Header
  RosTime stamp;
  std::string frame_id;
};

struct Vector3 {  // geometry_msgs/msg/Vector3 (and Point)
  double x = 0, y = 0, z = 0;
};

struct Quaternion {  // geometry_msgs/msg/Quaternion
  double x = 0, y = 0, z = 0, w = 1;
};

struct MultiArrayDimension {  // std_msgs/msg/MultiArrayDimension
  std::string label;
  std::uint32_t size = 0;
  std::uint32_t stride = 0;
};

struct Float32MultiArray {               // std_msgs/msg/Float32MultiArray
  std::vector<MultiArrayDimension> dim;  // layout.dim
  std::uint32_t data_offset = 0;         // layout.data_offset
  std::vector<float> data;
};

struct Odometry {  // nav_msgs/msg/Odometry
  RosHeader header;
  std::string child_frame_id;
  Vector3 position;        // pose.pose.position
  Quaternion orientation;  // pose.pose.orientation
  std::array<double, 36> pose_covariance{};
  Vector3 linear;   // twist.twist.linear
  Vector3 angular;  // twist.twist.angular
  std::array<double, 36> twist_covariance{};
};

struct LaserScan {  // sensor_msgs/msg/LaserScan
  RosHeader header;
  float angle_min = 0, angle_max = 0, angle_increment = 0;
  float time_increment = 0, scan_time = 0;
  float range_min = 0, range_max = 0;
  std::vector<float> ranges;
  std::vector<float> intensities;
};

struct TransformStamped {  // geometry_msgs/msg/TransformStamped
  RosHeader header;
  std::string child_frame_id;
  Vector3 translation;
  Quaternion rotation;
};

struct TfMessage {  // tf2_msgs/msg/TFMessage
  std::vector<TransformStamped> transforms;
};

/// Type strings as they appear in bags.
inline constexpr const char* kFloat32MultiArrayType = "std_msgs/msg/Float32MultiArray";
inline constexpr const char* kOdometryType = "nav_msgs/msg/Odometry";
inline constexpr const char* kLaserScanType = "sensor_msgs/msg/LaserScan";
inline constexpr const char* kTfMessageType = "tf2_msgs/msg/TFMessage";

}  // namespace uwbsar::rosbag
