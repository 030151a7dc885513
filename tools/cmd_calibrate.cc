// `uwbsar calibrate BAG [--ground-truth TUM] [--segment-m M] [--out FILE.yaml]`: measures the
// base's odometry calibration once, on a run with ground truth (motion capture, a surveyed
// path, the simulator's topic), and prints it as the backend.calibration_*_mean keys
// (slam/calibrate_job.h). --out writes them as a configuration file.
#include <cmath>
#include <cstdio>

#include "slam/calibrate_job.h"
#include "tools/commands.h"

namespace uwbsar::tools {
namespace {

struct CalibrateOptions {
  std::string bag, ground_truth, out;
  double segment_m = 0.5;
};

void PrintFit(const CalibrationFit& fit) {
  const char* names[3] = {"distance scale", "heading drift (rad/m)", "rotation scale"};
  std::printf("segments: %d over %.2f m of odometry and %.2f rad of turns\n", fit.segments,
              fit.path_m, fit.abs_turn_rad);
  for (int i = 0; i < 3; ++i) {
    if (fit.observed[i]) {
      std::printf("%-22s %+.6f +- %.6f\n", names[i], fit.calibration[i], fit.sigma[i]);
    } else {
      std::printf("%-22s %+.6f (not observed by this run: the configured mean)\n", names[i],
                  fit.calibration[i]);
    }
  }
  std::printf("per-segment error: %.3f -> %.3f cm, %.4f -> %.4f deg\n", fit.xy_rms_before_m * 100,
              fit.xy_rms_after_m * 100, fit.yaw_rms_before_rad * 180 / M_PI,
              fit.yaw_rms_after_rad * 180 / M_PI);
}

}  // namespace

void AddCalibrateCommand(CLI::App& app, const GlobalOptions& globals) {
  auto opts = std::make_shared<CalibrateOptions>();
  CLI::App* cmd = app.add_subcommand(
      "calibrate", "Measure the base's odometry calibration on a run with ground truth");
  cmd->add_option("BAG", opts->bag, "Bag directory (metadata.yaml), .db3 or .mcap file")
      ->required();
  cmd->add_option("--ground-truth", opts->ground_truth,
                  "TUM trajectory of the true poses (default: the bag's ground-truth topic)")
      ->check(InputFile());
  cmd->add_option("--segment-m", opts->segment_m, "Odometry path per fitted segment")
      ->check(CheckPositiveFinite);
  cmd->add_option("--out", opts->out, "Write the calibration as a configuration file (YAML)")
      ->check(OutputPath("--out"));
  cmd->callback([opts, &globals] {
    const Config config = LoadConfigFor(globals);
    RefuseOutputsOnInputs(
        globals, {{"--out", opts->out}},
        {{"the input bag", opts->bag}, {"the --ground-truth file", opts->ground_truth}});
    slam::CalibrateJobOptions options;
    options.bag = opts->bag;
    options.ground_truth_tum = opts->ground_truth;
    options.out_yaml = opts->out;
    options.segment_m = opts->segment_m;
    const slam::CalibrateJobResult result = slam::RunCalibrateJob(config, options);
    const CalibrationFit& fit = result.fit;
    const std::string& yaml = result.yaml;
    // -q: only the result, the configuration keys, and only when no file receives them.
    if (globals.quiet) {
      if (opts->out.empty()) std::printf("%s", yaml.c_str());
      return;
    }
    PrintFit(fit);
    std::printf("\n%s", yaml.c_str());
    if (!opts->out.empty()) std::printf("wrote %s\n", opts->out.c_str());
  });
}

}  // namespace uwbsar::tools
