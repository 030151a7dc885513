#include "slam/jobs/info_job.h"

#include <cstdio>

#include "drivers/rosbag/bag_info_text.h"
#include "drivers/rosbag/bag_reader.h"
#include "drivers/rosbag/robot_bag.h"

namespace uwbsar::slam {
namespace {

std::string Format(const char* fmt, const std::string& text, unsigned long long n) {
  const int size = std::snprintf(nullptr, 0, fmt, text.c_str(), n);
  std::string out(static_cast<std::size_t>(size) + 1, '\0');
  std::snprintf(out.data(), out.size(), fmt, text.c_str(), n);
  out.resize(static_cast<std::size_t>(size));
  return out;
}

}  // namespace

std::string BagInfoText(const std::string& bag) {
  const rosbag::BagReader reader(bag);
  return rosbag::FormatBagInfo(reader.Info());
}

std::string BagDecodeText(const std::string& bag, const Config& config) {
  rosbag::RobotBagVisitor ignore;
  const rosbag::RobotBagStats s =
      rosbag::ReadRobotBag(bag, rosbag::RobotBagOptionsFromConfig(config), ignore);
  char line[512];
  std::snprintf(
      line, sizeof(line),
      "Decoded:           %llu messages: %llu radar scans, %llu odometry, %llu ground "
      "truth, %llu laser scans, %llu tf, %llu skipped\n",
      static_cast<unsigned long long>(s.messages), static_cast<unsigned long long>(s.radar_scans),
      static_cast<unsigned long long>(s.odometry), static_cast<unsigned long long>(s.ground_truth),
      static_cast<unsigned long long>(s.laser_scans), static_cast<unsigned long long>(s.tf),
      static_cast<unsigned long long>(s.skipped));
  std::string text = line;
  for (const auto& [type, n] : s.skipped_by_type) {
    text += Format("Skipped type:      %s (%llu)\n", type, static_cast<unsigned long long>(n));
  }
  return text;
}

}  // namespace uwbsar::slam
