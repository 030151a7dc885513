// `uwbsar info BAG`: what is in a ROS 2 bag (directory, .db3 or .mcap), laid out like
// `ros2 bag info`; --decode also decodes every message of the known types and reports
// what the SLAM pipeline would receive (slam/jobs/info_job.h).
#include <iostream>

#include "slam/jobs/info_job.h"
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
    std::cout << slam::BagInfoText(opts->bag);
    if (!opts->decode) return;
    std::cout << slam::BagDecodeText(opts->bag, LoadConfigFor(globals));
  });
}

}  // namespace uwbsar::tools
