// The ROS 2 messages the project reads and writes, field for field as their .msg
// definitions (std_msgs, geometry_msgs, nav_msgs, sensor_msgs, tf2_msgs), so a
// decode/encode round trip loses nothing. The result messages (OccupancyGrid, Path, Image,
// MarkerArray: results.mcap) are written only and hold the fields uwbsar fills; the encoder
// writes every other field of the Humble definition empty.
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

struct RosPose {  // geometry_msgs/msg/Pose
  Vector3 position;
  Quaternion orientation;
};

struct OccupancyGridMessage {  // nav_msgs/msg/OccupancyGrid
  RosHeader header;
  RosTime map_load_time;  // info.map_load_time
  float resolution = 0;   // info.resolution
  std::uint32_t width = 0, height = 0;
  RosPose origin;
  std::vector<std::int8_t> data;  // row-major, row 0 = the BOTTOM row (smallest y)
};

struct PoseStamped {  // geometry_msgs/msg/PoseStamped
  RosHeader header;
  RosPose pose;
};

struct PathMessage {  // nav_msgs/msg/Path
  RosHeader header;
  std::vector<PoseStamped> poses;
};

struct ImageMessage {  // sensor_msgs/msg/Image
  RosHeader header;
  std::uint32_t height = 0, width = 0;
  std::string encoding;  // e.g. "mono8", "rgb8"
  std::uint8_t is_bigendian = 0;
  std::uint32_t step = 0;  // bytes per row
  std::vector<std::uint8_t> data;
};

struct ColorRgba {  // std_msgs/msg/ColorRGBA
  float r = 0, g = 0, b = 0, a = 1;
};

struct Marker {  // visualization_msgs/msg/Marker (Humble); texture and mesh fields empty
  static constexpr std::int32_t kLineList = 5;
  static constexpr std::int32_t kSphereList = 7;
  static constexpr std::int32_t kAdd = 0;
  static constexpr std::int32_t kDeleteAll = 3;
  RosHeader header;
  std::string ns;
  std::int32_t id = 0;
  std::int32_t type = 0;
  std::int32_t action = kAdd;
  RosPose pose;
  Vector3 scale;
  ColorRgba color;
  std::vector<Vector3> points;
  std::string text;
};

struct MarkerArray {  // visualization_msgs/msg/MarkerArray
  std::vector<Marker> markers;
};

/// Type strings as they appear in bags.
inline constexpr const char* kFloat32MultiArrayType = "std_msgs/msg/Float32MultiArray";
inline constexpr const char* kOdometryType = "nav_msgs/msg/Odometry";
inline constexpr const char* kLaserScanType = "sensor_msgs/msg/LaserScan";
inline constexpr const char* kTfMessageType = "tf2_msgs/msg/TFMessage";
inline constexpr const char* kOccupancyGridType = "nav_msgs/msg/OccupancyGrid";
inline constexpr const char* kPathType = "nav_msgs/msg/Path";
inline constexpr const char* kImageType = "sensor_msgs/msg/Image";
inline constexpr const char* kMarkerArrayType = "visualization_msgs/msg/MarkerArray";

}  // namespace uwbsar::rosbag
