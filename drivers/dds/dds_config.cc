#include "drivers/dds/dds_config.h"

#include <string>
#include <utility>

#include "core/config_require.h"

namespace uwbsar {

using config_validation::Require;

void Validate(const DdsConfig& d, const std::string& src) {
  const std::string k = "dds.";
  // DDS domain ids map to UDP ports; 232 is the largest that fits (ROS 2 documents 0-232).
  Require(d.domain_id >= -1 && d.domain_id <= 232, src, k + "domain_id",
          "must be -1 ($ROS_DOMAIN_ID) or in [0, 232]");
  Require(d.reliability == "reliable" || d.reliability == "best_effort", src, k + "reliability",
          "must be 'reliable' or 'best_effort'");
  Require(d.history_depth >= 1, src, k + "history_depth", "must be >= 1");
  for (const auto& [key, topic] :
       {std::make_pair("map_topic", &d.map_topic), std::make_pair("pose_topic", &d.pose_topic),
        std::make_pair("path_topic", &d.path_topic),
        std::make_pair("loops_topic", &d.loops_topic)}) {
    Require(!topic->empty() && (*topic)[0] == '/', src, k + key,
            "must be an absolute ROS 2 topic name (starting with '/')");
  }
  Require(!d.map_frame.empty(), src, k + "map_frame", "must not be empty");
  Require(!d.odom_frame.empty() && d.odom_frame != d.map_frame, src, k + "odom_frame",
          "must not be empty nor equal to dds.map_frame");
  Require(d.publish_pose_period_s >= 0, src, k + "publish_pose_period_s", "must be >= 0");
  Require(d.silence_timeout_s >= 0, src, k + "silence_timeout_s", "must be >= 0");
  Require(d.reorder_window_s >= 0 && d.reorder_window_s <= 10, src, k + "reorder_window_s",
          "must be in [0, 10]");
  Require(d.startup_hold_s >= 0 && d.startup_hold_s <= 60, src, k + "startup_hold_s",
          "must be in [0, 60]");
}

}  // namespace uwbsar
