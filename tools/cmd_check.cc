// `uwbsar check BAG`: a recording against the configuration before mapping it, one line per
// check (slam/jobs/check_job.h); exit 3 when something would make `map` fail or lose data.
#include <cstdio>

#include "core/errors.h"
#include "slam/jobs/check_job.h"
#include "tools/commands.h"

namespace uwbsar::tools {

void AddCheckCommand(CLI::App& app, const GlobalOptions& globals) {
  auto bag = std::make_shared<std::string>();
  CLI::App* cmd = app.add_subcommand(
      "check",
      "Check a ROS 2 bag against the configuration before mapping it: topics and types, "
      "samples per scan, scan and odometry rates, stamps, odometry jumps");
  cmd->add_option("BAG", *bag, "Bag directory (metadata.yaml), .db3 or .mcap file")
      ->required()
      ->check(InputPath());
  cmd->callback([bag, &globals] {
    const slam::BagCheck check = slam::CheckBag(LoadConfigFor(globals), *bag);
    for (const slam::CheckLine& line : check.lines) {
      if (globals.quiet && line.level != slam::CheckLevel::kError) continue;
      std::printf("%s\n", slam::FormatCheckLine(line).c_str());
    }
    const int errors = check.Count(slam::CheckLevel::kError);
    const int warnings = check.Count(slam::CheckLevel::kWarning);
    if (errors > 0) {
      std::fflush(stdout);  // the lines before the refusal on stderr
      throw InputError(*bag + ": " + std::to_string(errors) + (errors == 1 ? " check" : " checks") +
                       " failed (the error lines above): map would fail or lose data");
    }
    if (!globals.quiet) {
      std::printf("%s\n", warnings == 0 ? "all ok"
                                        : (std::to_string(warnings) + " warning" +
                                           (warnings == 1 ? "" : "s") + ", no error")
                                              .c_str());
    }
  });
}

}  // namespace uwbsar::tools
