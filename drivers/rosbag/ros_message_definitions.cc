// The ros2msg definitions of the types the project writes. The text follows the
// public .msg files; dependencies are appended as rosbag2's MCAP plugin does, so
// Foxglove and `ros2 bag` can decode our recordings without the packages installed.
#include <map>
#include <string>
#include <vector>

#include "drivers/rosbag/ros_codecs.h"

namespace uwbsar::rosbag {
namespace {

const std::map<std::string, std::string>& Bodies() {
  static const std::map<std::string, std::string> bodies = {
      {"std_msgs/msg/Float32MultiArray", "std_msgs/MultiArrayLayout layout\nfloat32[] data\n"},
      {"std_msgs/MultiArrayLayout", "std_msgs/MultiArrayDimension[] dim\nuint32 data_offset\n"},
      {"std_msgs/MultiArrayDimension", "string label\nuint32 size\nuint32 stride\n"},
      {"nav_msgs/msg/Odometry",
       "std_msgs/Header header\nstring child_frame_id\ngeometry_msgs/PoseWithCovariance pose\n"
       "geometry_msgs/TwistWithCovariance twist\n"},
      {"std_msgs/Header", "builtin_interfaces/Time stamp\nstring frame_id\n"},
      {"builtin_interfaces/Time", "int32 sec\nuint32 nanosec\n"},
      {"geometry_msgs/PoseWithCovariance", "geometry_msgs/Pose pose\nfloat64[36] covariance\n"},
      {"geometry_msgs/Pose",
       "geometry_msgs/Point position\ngeometry_msgs/Quaternion orientation\n"},
      {"geometry_msgs/Point", "float64 x\nfloat64 y\nfloat64 z\n"},
      {"geometry_msgs/Quaternion", "float64 x\nfloat64 y\nfloat64 z\nfloat64 w\n"},
      {"geometry_msgs/TwistWithCovariance", "geometry_msgs/Twist twist\nfloat64[36] covariance\n"},
      {"geometry_msgs/Twist", "geometry_msgs/Vector3 linear\ngeometry_msgs/Vector3 angular\n"},
      {"geometry_msgs/Vector3", "float64 x\nfloat64 y\nfloat64 z\n"},
      {"sensor_msgs/msg/LaserScan",
       "std_msgs/Header header\nfloat32 angle_min\nfloat32 angle_max\nfloat32 angle_increment\n"
       "float32 time_increment\nfloat32 scan_time\nfloat32 range_min\nfloat32 range_max\n"
       "float32[] ranges\nfloat32[] intensities\n"},
      {"tf2_msgs/msg/TFMessage", "geometry_msgs/TransformStamped[] transforms\n"},
      {"geometry_msgs/TransformStamped",
       "std_msgs/Header header\nstring child_frame_id\ngeometry_msgs/Transform transform\n"},
      {"geometry_msgs/Transform",
       "geometry_msgs/Vector3 translation\ngeometry_msgs/Quaternion rotation\n"},
  };
  return bodies;
}

// Dependencies in first-use order (depth first), as rosbag2 lists them.
const std::map<std::string, std::vector<std::string>>& Dependencies() {
  static const std::map<std::string, std::vector<std::string>> deps = {
      {"std_msgs/msg/Float32MultiArray",
       {"std_msgs/MultiArrayLayout", "std_msgs/MultiArrayDimension"}},
      {"nav_msgs/msg/Odometry",
       {"std_msgs/Header", "builtin_interfaces/Time", "geometry_msgs/PoseWithCovariance",
        "geometry_msgs/Pose", "geometry_msgs/Point", "geometry_msgs/Quaternion",
        "geometry_msgs/TwistWithCovariance", "geometry_msgs/Twist", "geometry_msgs/Vector3"}},
      {"sensor_msgs/msg/LaserScan", {"std_msgs/Header", "builtin_interfaces/Time"}},
      {"tf2_msgs/msg/TFMessage",
       {"geometry_msgs/TransformStamped", "std_msgs/Header", "builtin_interfaces/Time",
        "geometry_msgs/Transform", "geometry_msgs/Vector3", "geometry_msgs/Quaternion"}},
  };
  return deps;
}

}  // namespace

std::string RosMessageDefinition(const std::string& type) {
  const auto deps = Dependencies().find(type);
  if (deps == Dependencies().end()) return {};
  std::string text = Bodies().at(type);
  for (const auto& dep : deps->second) {
    text += std::string(80, '=') + "\nMSG: " + dep + "\n" + Bodies().at(dep);
  }
  return text;
}

}  // namespace uwbsar::rosbag
