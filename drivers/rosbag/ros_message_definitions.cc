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
      {"nav_msgs/msg/OccupancyGrid",
       "std_msgs/Header header\nnav_msgs/MapMetaData info\nint8[] data\n"},
      {"nav_msgs/MapMetaData",
       "builtin_interfaces/Time map_load_time\nfloat32 resolution\nuint32 width\nuint32 height\n"
       "geometry_msgs/Pose origin\n"},
      {"nav_msgs/msg/Path", "std_msgs/Header header\ngeometry_msgs/PoseStamped[] poses\n"},
      {"geometry_msgs/PoseStamped", "std_msgs/Header header\ngeometry_msgs/Pose pose\n"},
      {"sensor_msgs/msg/Image",
       "std_msgs/Header header\nuint32 height\nuint32 width\nstring encoding\n"
       "uint8 is_bigendian\nuint32 step\nuint8[] data\n"},
      {"visualization_msgs/msg/MarkerArray", "visualization_msgs/Marker[] markers\n"},
      {"visualization_msgs/Marker",
       "int32 LINE_LIST=5\nint32 SPHERE_LIST=7\nint32 ADD=0\nint32 DELETEALL=3\n"
       "std_msgs/Header header\nstring ns\nint32 id\nint32 type\nint32 action\n"
       "geometry_msgs/Pose pose\ngeometry_msgs/Vector3 scale\nstd_msgs/ColorRGBA color\n"
       "builtin_interfaces/Duration lifetime\nbool frame_locked\ngeometry_msgs/Point[] points\n"
       "std_msgs/ColorRGBA[] colors\nstring texture_resource\n"
       "sensor_msgs/CompressedImage texture\nvisualization_msgs/UVCoordinate[] uv_coordinates\n"
       "string text\nstring mesh_resource\nvisualization_msgs/MeshFile mesh_file\n"
       "bool mesh_use_embedded_materials\n"},
      {"std_msgs/ColorRGBA", "float32 r\nfloat32 g\nfloat32 b\nfloat32 a\n"},
      {"builtin_interfaces/Duration", "int32 sec\nuint32 nanosec\n"},
      {"sensor_msgs/CompressedImage", "std_msgs/Header header\nstring format\nuint8[] data\n"},
      {"visualization_msgs/UVCoordinate", "float32 u\nfloat32 v\n"},
      {"visualization_msgs/MeshFile", "string filename\nuint8[] data\n"},
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
      {"nav_msgs/msg/OccupancyGrid",
       {"std_msgs/Header", "builtin_interfaces/Time", "nav_msgs/MapMetaData", "geometry_msgs/Pose",
        "geometry_msgs/Point", "geometry_msgs/Quaternion"}},
      {"nav_msgs/msg/Path",
       {"std_msgs/Header", "builtin_interfaces/Time", "geometry_msgs/PoseStamped",
        "geometry_msgs/Pose", "geometry_msgs/Point", "geometry_msgs/Quaternion"}},
      {"sensor_msgs/msg/Image", {"std_msgs/Header", "builtin_interfaces/Time"}},
      {"visualization_msgs/msg/MarkerArray",
       {"visualization_msgs/Marker", "std_msgs/Header", "builtin_interfaces/Time",
        "geometry_msgs/Pose", "geometry_msgs/Point", "geometry_msgs/Quaternion",
        "geometry_msgs/Vector3", "std_msgs/ColorRGBA", "builtin_interfaces/Duration",
        "sensor_msgs/CompressedImage", "visualization_msgs/UVCoordinate",
        "visualization_msgs/MeshFile"}},
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
