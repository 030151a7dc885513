// `uwbsar info BAG`: what is in a ROS 2 bag (directory, .db3 or .mcap), laid out like
// `ros2 bag info`; --decode also decodes every message of the known types and reports
// what the SLAM pipeline would receive.
#include <cstdio>
#include <iostream>

#include "drivers/rosbag/bag_info_text.h"
#include "drivers/rosbag/bag_reader.h"
#include "drivers/rosbag/robot_bag.h"
#include "tools/commands.h"

namespace uwbsar::tools {

void AddInfoCommand(CLI::App& app, const GlobalOptions& globals) {
  struct Options {
    std::string bag;
    bool decode = false;
  };
  auto opts = std::make_shared<Options>();
  CLI::App* cmd = app.add_subcommand("info", "Show the topics, counts and times of a ROS 2 bag");
  cmd->add_option("BAG", opts->bag, "Bag directory (metadata.yaml), .db3 or .mcap file")
      ->required();
  cmd->add_flag("--decode", opts->decode,
                "Also decode every message (checks the whole bag; uses the --config topics)");
  cmd->callback([opts, &globals] {
    const rosbag::BagReader reader(opts->bag);
    std::cout << rosbag::FormatBagInfo(reader.Info());
    if (!opts->decode) return;
    const auto options = rosbag::RobotBagOptionsFromConfig(LoadConfigFor(globals));
    rosbag::RobotBagVisitor ignore;
    const rosbag::RobotBagStats s = rosbag::ReadRobotBag(opts->bag, options, ignore);
    std::printf(
        "Decoded:           %llu messages: %llu radar scans, %llu odometry, %llu ground "
        "truth, %llu laser scans, %llu tf, %llu skipped\n",
        static_cast<unsigned long long>(s.messages), static_cast<unsigned long long>(s.radar_scans),
        static_cast<unsigned long long>(s.odometry),
        static_cast<unsigned long long>(s.ground_truth),
        static_cast<unsigned long long>(s.laser_scans), static_cast<unsigned long long>(s.tf),
        static_cast<unsigned long long>(s.skipped));
    for (const auto& [type, n] : s.skipped_by_type) {
      std::printf("Skipped type:      %s (%llu)\n", type.c_str(),
                  static_cast<unsigned long long>(n));
    }
  });
}

}  // namespace uwbsar::tools
