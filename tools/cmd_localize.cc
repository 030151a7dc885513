// `uwbsar localize BAG --map SESSION --out DIR`: localise a log in a saved map without
// changing it (slam/localization/localize_job.h).
#include <cstdio>

#include "slam/app_config.h"
#include "slam/jobs/saved_session.h"
#include "slam/localization/localize_job.h"
#include "slam/outputs/localize_outputs.h"
#include "slam/outputs/map_outputs.h"
#include "slam/outputs/navigation_map.h"
#include "slam/outputs/results_timeline.h"
#include "slam/session/session_file.h"
#include "tools/commands.h"

namespace uwbsar::tools {

void AddLocalizeCommand(CLI::App& app, const GlobalOptions& globals) {
  struct Options {
    std::string bag, map, out_dir;
  };
  auto opts = std::make_shared<Options>();
  CLI::App* cmd = app.add_subcommand(
      "localize", "Localise a ROS 2 bag in a saved map (session.uwbsar); the map is not changed");
  cmd->add_option("bag", opts->bag, "Bag directory, .db3 or .mcap")->required();
  cmd->add_option("--map", opts->map, "Saved session (folder or session.uwbsar)")->required();
  cmd->add_option("--out", opts->out_dir, "Output folder")->required()->check(OutputPath("--out"));
  cmd->callback([opts, &globals] {
    const Config config = LoadConfigFor(globals);
    // Nothing is created before the inputs are accepted: the outputs are checked, the map
    // read (its folder locked shared), and only then the output folder made and locked for
    // the whole run. Neither can change under the run, and the outputs never go into a
    // map's folder (checked again under the lock).
    slam::RefuseMapFolderForLocalize(opts->out_dir);
    RefuseOutputsOnInputs(
        globals, {{"--out", opts->out_dir}},
        {{"the input bag", opts->bag}, SessionInput("the --map session", opts->map)});
    slam::CheckOutputFolder(opts->out_dir);
    const slam::SavedSession map = slam::OpenSavedSession(opts->map, config);
    // results.mcap's /map is the map's own map.pgm, read (and checked) before the work.
    const OccupancyGrid map_grid = config.slam.results_mcap
                                       ? slam::SavedNavigationGrid(map.dir, map.data, config)
                                       : OccupancyGrid{};
    const FolderLock out_lock = slam::LockOutputFolder(opts->out_dir);
    slam::RefuseMapFolderForLocalize(opts->out_dir);
    const slam::LocalizeRun run = slam::LocalizeBag(map.data, config, opts->bag, !globals.quiet);
    const nlohmann::json s =
        slam::WriteLocalizeOutputs(run, opts->out_dir, &map.data, &config, &map_grid);
    if (globals.quiet) return;
    std::printf(
        "localised %.1f s of log in %.2f s: %zu keyframes (%d tracking, %d lost, %d "
        "relocalised)\n",
        run.log_duration_s, run.processing_s, run.keyframes.size(),
        s["localization"]["tracking"].get<int>(), s["localization"]["lost"].get<int>(),
        s["localization"]["relocalised"].get<int>());
    if (run.first_fix >= 0) {
      std::printf("first fix after %.2f m (%.1f s of log)\n", run.first_fix_path_m,
                  run.first_fix_time_s);
    } else {
      std::printf("never placed in the map: lost\n");
    }
    if (s.contains("ate") && s["ate"].is_object()) {  // as map prints it, from the first fix
      std::printf("ATE RMSE %.2f cm (odometry alone %.2f cm) over %d poses, from the first fix\n",
                  s["ate"]["rmse_m"].get<double>() * 100,
                  s["odometry_ate"]["rmse_m"].get<double>() * 100, s["ate"]["poses"].get<int>());
    } else {
      std::printf("no ground truth or no fix: ATE not computed\n");
    }
    std::vector<std::string> written = {"trajectory.tum", "localize.csv", "summary.json"};
    if (config.slam.results_mcap) written.insert(written.end() - 1, slam::kResultsMcapName);
    PrintWrittenFolder(opts->out_dir, written, globals);
  });
}

}  // namespace uwbsar::tools
