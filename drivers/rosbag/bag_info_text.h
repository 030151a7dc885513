// The text of `uwbsar info BAG`, laid out like `ros2 bag info` so that people who
// live in ROS 2 read it at a glance.
#pragma once

#include <string>

#include "drivers/rosbag/bag_reader.h"

namespace uwbsar::rosbag {

std::string FormatBagInfo(const BagInfo& info);
/// "1.2 MiB" style sizes, as ros2 bag info prints them.
std::string HumanBytes(std::uint64_t bytes);
/// "Aug 27 2025 18:25:42.123456789 (1756311942.123456789)" in local time.
std::string FormatBagTime(TimestampNs t);

}  // namespace uwbsar::rosbag
