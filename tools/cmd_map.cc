// `uwbsar map BAG --out DIR`: the main job on a recorded (or simulated) bag.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <optional>

#include "slam/app_config.h"
#include "slam/map_job.h"
#include "slam/outputs/map_outputs.h"
#include "slam/outputs/session_capture.h"
#include "slam/session/session_file.h"
#include "tools/commands.h"
#include "tools/map_resume.h"

namespace uwbsar::tools {

namespace {

/// A gyro base's bias as this run estimated it (it belongs to the run: never calibrated).
void PrintGyroBias(const slam::SlamSystem& slam) {
  const auto biases = slam.graph().GyroBiases();
  auto it = biases.find(0);
  if (it == biases.end() || it->second.empty()) return;
  double sum = 0.0, lo = it->second.front().second, hi = lo;
  for (const auto& [t_s, b] : it->second) sum += b, lo = std::min(lo, b), hi = std::max(hi, b);
  constexpr double kDegPerRad = 180.0 / M_PI;
  std::printf(
      "gyro bias of this run: %+.4f deg/s (%+.4f .. %+.4f over %zu segments; %zu standstills "
      "measured it)\n",
      kDegPerRad * sum / static_cast<double>(it->second.size()), kDegPerRad * lo, kDegPerRad * hi,
      it->second.size(), slam.standstills().size());
}

}  // namespace

void PrintMapSummary(const slam::MapRun& run, const slam::MapOutputs& outputs,
                     const std::string& out_dir, const GlobalOptions& globals) {
  if (globals.quiet) return;
  const auto& s = outputs.summary;
  std::printf("mapped %.1f s of log (%.1f m) in %.2f s: real-time factor %.1f\n",
              run.log_duration_s(), s["path_length_m"].get<double>(), run.processing_s,
              s["real_time_factor"].get<double>());
  std::printf("%zu keyframes, %d loops accepted of %zu candidates (%d rejected by the backend)\n",
              run.slam->keyframes().size(), s["loops"]["accepted"].get<int>(),
              run.slam->loops().size(), s["loops"]["rejected_by_backend"].get<int>());
  if (outputs.ate.num_poses > 0) {
    std::printf("ATE RMSE %.2f cm (odometry alone %.2f cm) over %d poses\n",
                outputs.ate.rmse_m * 100, outputs.odometry_ate.rmse_m * 100, outputs.ate.num_poses);
  } else {
    std::printf("no ground truth: ATE not computed\n");
  }
  std::printf("peak memory %.0f MiB\n", s["peak_memory_mib"].get<double>());
  PrintOdometryCalibration(run.slam->config(), globals);
  PrintGyroBias(*run.slam);
  std::printf("report: %s/report.html\n", out_dir.c_str());
  PrintWrittenFolder(out_dir, outputs.files, globals);
}

void AddMapCommand(CLI::App& app, const GlobalOptions& globals) {
  struct Options {
    std::string bag, out_dir, ground_truth, resume;
    bool exact = false;
    bool skip_damaged = false;
    bool overwrite = false;
  };
  auto opts = std::make_shared<Options>();
  CLI::App* cmd = app.add_subcommand("map", "Map a ROS 2 bag: trajectory, loops, global SAR map");
  cmd->add_option("bag", opts->bag, "Bag directory, .db3 or .mcap")->required();
  cmd->add_option("--out", opts->out_dir, "Output folder")->required()->check(OutputPath("--out"));
  cmd->add_option("--ground-truth", opts->ground_truth,
                  "TUM trajectory to evaluate against (default: the bag's ground-truth topic)")
      ->check(InputFile());
  cmd->add_flag("--exact", opts->exact,
                "Also write map_exact.png / map_exact_float.tif: every scan back-projected again "
                "at its corrected pose, at the imaging resolution");
  cmd->add_flag("--skip-damaged", opts->skip_damaged,
                "MCAP: skip a chunk that fails its CRC or cannot be decompressed (warns with its "
                "offset and message count) instead of failing the whole run");
  cmd->add_option("--resume", opts->resume,
                  "Continue a saved session (folder or session.uwbsar): this run joins its map "
                  "as a new trajectory once a loop places it (refused, leaving it unchanged, when "
                  "no loop does or when it already holds this recording)");
  cmd->add_flag("--overwrite", opts->overwrite,
                "Replace the saved map (session.uwbsar) that --out already holds; without it such "
                "a folder is refused unless it is the --resume session's own");
  cmd->callback([opts, &globals] {
    Config config = LoadConfigFor(globals);
    // The --resume session's folder may be the output: the join replaces its outputs as one
    // set (slam::RefuseToReplaceSavedMap).
    RefuseOutputsOnInputs(
        globals, {{"--out", opts->out_dir}},
        {{"the input bag", opts->bag}, {"the --ground-truth file", opts->ground_truth}});
    if (opts->exact) config.slam.keep_scan_profiles = true;  // the exact map re-images them
    // Every input and output is checked before the work: the ground truth is read, the
    // output folder locked and its staging folder created, the saved session read (an
    // incompatible one, or one that holds this recording already, is refused first).
    std::vector<OdometrySample> ground_truth;
    if (!opts->ground_truth.empty()) {
      ground_truth = slam::ReadGroundTruthFile(opts->ground_truth, config.limits.max_input_file_mb);
    }
    slam::MapOutputStage stage(opts->out_dir);
    std::optional<slam::SavedSession> saved;
    const std::string fingerprint = slam::BagFingerprint(opts->bag);  // opens the bag
    if (!opts->resume.empty()) {
      saved = OpenSessionToResume(opts->resume, opts->bag, fingerprint, config);
    }
    slam::RefuseToReplaceSavedMap(
        opts->out_dir, saved ? std::vector<std::string>{saved->dir} : std::vector<std::string>{},
        opts->overwrite,
        "give another --out, --resume " + opts->out_dir +
            " to extend it, or --overwrite to "
            "replace it");
    rosbag::BagReadOptions read_options;
    read_options.skip_damaged_chunks = opts->skip_damaged;
    slam::MapRun run = slam::MapBag(config, opts->bag, !globals.quiet, read_options);
    if (!opts->ground_truth.empty()) run.ground_truth = std::move(ground_truth);
    run.fingerprint = fingerprint;
    if (!opts->resume.empty()) {
      WriteResumedMap(*saved, run, &stage, opts->out_dir, globals);
      return;
    }
    slam::SaveSessionWithOutputs(&stage, run);
    slam::MapOutputOptions output_options;
    output_options.exact = opts->exact;
    const slam::MapOutputs outputs = stage.Commit(run, output_options);
    PrintMapSummary(run, outputs, opts->out_dir, globals);
  });
}

}  // namespace uwbsar::tools
