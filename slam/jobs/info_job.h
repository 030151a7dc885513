// The job behind `uwbsar info BAG`: what a ROS 2 bag (directory, .db3 or .mcap) holds, as
// text laid out like `ros2 bag info` (drivers/rosbag/bag_info_text.h), and what decoding every
// message of the known types gives the SLAM system (drivers/rosbag/robot_bag.h).
#pragma once

#include <string>

#include "slam/app_config.h"

namespace uwbsar::slam {

/// The bag's topics, counts and times, as `ros2 bag info` prints them (ends in a newline).
/// Reads the metadata only; throws InputError naming the bag when it cannot be opened.
std::string BagInfoText(const std::string& bag);

/// Decodes every message with the topics of `config` (checks the whole bag; InputError naming
/// the bag, topic and offset on a bad message) and says what was decoded: a "Decoded:" line
/// with the counts by kind, then one "Skipped type:" line per undecoded message type.
std::string BagDecodeText(const std::string& bag, const Config& config);

}  // namespace uwbsar::slam
