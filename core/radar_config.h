// Settings of radars[]: the robot's radars and their mounting, declared beside the code that owns
// them (shared by drivers, imaging and frontend, so in core/); the application configuration
// (slam/config/system_config.h, slam/app_config.h) assembles the sections, and core/config_io.h
// reads and writes any struct with a Visit(). config/default.yaml documents every field; a test
// keeps the two in sync.
#pragma once

#include <string>
#include <vector>

namespace uwbsar {

/// One radar: where it sits on the robot, where it looks, what it sees.
struct RadarConfig {
  std::string name = "left";                  ///< label used in logs and outputs
  std::string topic = "/UWBradar0/readings";  ///< bag / ROS 2 topic of its scans
  double mount_x_m = 0.0;                     ///< antenna position in the robot frame (x forward)
  double mount_y_m = 0.18;                    ///< antenna position in the robot frame (y left)
  double boresight_yaw_deg = 90.0;            ///< boresight direction in the robot frame
  double fov_half_angle_deg = 30.0;           ///< half of the effective beam width
  double min_range_m = 0.4;                   ///< pixels closer than this are not imaged
  double max_range_m = 3.0;                   ///< pixels farther than this are not imaged
  double range_offset_m = 0.0;                ///< range of sample 0 (cable/antenna delay)
  int num_samples = 1000;                     ///< expected samples per scan
  int zero_leading_samples = 1;               ///< samples zeroed before use (reference zeroes 1)

  /// A `radars:` list read over one in effect merges into it by `name` (core/config_io.h): a
  /// robot file that changes one radar's key keeps the other radar. An entry with a new name
  /// adds a radar from the defaults above, which must give this key (another radar's topic
  /// would be read twice).
  static constexpr const char* kListAddRequires = "topic";

  template <class V>
  void Visit(V& v) {
    v("name", name);
    v("topic", topic);
    v("mount_x_m", mount_x_m);
    v("mount_y_m", mount_y_m);
    v("boresight_yaw_deg", boresight_yaw_deg);
    v("fov_half_angle_deg", fov_half_angle_deg);
    v("min_range_m", min_range_m);
    v("max_range_m", max_range_m);
    v("range_offset_m", range_offset_m);
    v("num_samples", num_samples);
    v("zero_leading_samples", zero_leading_samples);
  }
};

/// The paper's robot: left radar looks to +90 deg, right radar to -90 deg.
inline std::vector<RadarConfig> DefaultRadars() {
  RadarConfig left;
  RadarConfig right;
  right.name = "right";
  right.topic = "/UWBradar1/readings";
  right.mount_y_m = -0.18;
  right.boresight_yaw_deg = -90.0;
  return {left, right};
}
/// "radars[NAME]", the radar as configuration messages name it (its index when it has no name):
/// a file's entries merge by name, so its index there need not be its index in effect.
inline std::string RadarKey(const std::vector<RadarConfig>& radars, std::size_t i) {
  return "radars[" + (radars[i].name.empty() ? std::to_string(i) : radars[i].name) + "]";
}

/// Semantic checks of radars[*]; throws ConfigError naming the dotted key.
void Validate(const std::vector<RadarConfig>& radars, const std::string& source_name);

}  // namespace uwbsar
