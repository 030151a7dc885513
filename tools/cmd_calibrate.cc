// `uwbsar calibrate BAG [--ground-truth TUM] [--segment-m M] [--base auto|gyro|wheel]
// [--out FILE.yaml]`: measures the base's odometry calibration once, on a run with ground truth
// (motion capture, a surveyed path, the simulator's topic), and prints the backend keys that
// belong to the robot (slam/jobs/calibrate_job.h); a gyro base's bias is the run's: reported in one
// line, not written. --out writes the keys as a configuration file.
#include <algorithm>
#include <cmath>
#include <cstdio>

#include "slam/jobs/calibrate_job.h"
#include "tools/commands.h"

namespace uwbsar::tools {
namespace {

struct CalibrateOptions {
  std::string bag, ground_truth, out, base = "auto";
  double segment_m = 0.5;
};

constexpr double kDegPerRad = 180.0 / M_PI;

/// "base: gyro (...)": the model fitted and why.
void PrintModel(const CalibrationFit& fit, const BackendConfig& config) {
  const CalibrationModelEvidence& e = fit.evidence;
  std::printf("base: %s (", EnumName(fit.model));
  if (e.told) {
    std::printf("--base");
  } else if (e.decided_by == "residuals") {
    std::printf("detected: a %s explains the heading, chi2 %.0f against %.0f for a %s",
                fit.model == OdometryModel::kGyro ? "gyro bias per second" : "drift per metre",
                std::min(e.gyro_chi2, e.wheel_chi2), std::max(e.gyro_chi2, e.wheel_chi2),
                fit.model == OdometryModel::kGyro ? "drift per metre" : "gyro bias per second");
  } else if (e.decided_by == "standstills") {
    if (fit.model == OdometryModel::kGyro) {
      std::printf("detected: its heading turned %.3f deg in %.1f s standing still",
                  e.still_turn_rad * kDegPerRad, e.still_s);
    } else {
      std::printf("detected: its heading did not move in %.1f s standing still", e.still_s);
    }
  } else {
    std::printf("backend.odometry_model: this run fits both kinds alike and has no standstill");
  }
  std::printf(")\n");
  if (fit.model != config.odometry_model) {
    std::printf("the configuration's backend.odometry_model is %s: the keys below set %s\n",
                EnumName(config.odometry_model), EnumName(fit.model));
  }
}

void PrintFit(const CalibrationFit& fit, const BackendConfig& config) {
  const char* names[3] = {"distance scale", "heading drift (rad/m)", "rotation scale"};
  PrintModel(fit, config);
  std::printf("segments: %d over %.2f m of odometry and %.2f rad of turns\n", fit.segments,
              fit.path_m, fit.abs_turn_rad);
  for (int i = 0; i < 3; ++i) {
    if (fit.model == OdometryModel::kGyro && i == kCalibHeadingDrift) continue;
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
  if (fit.model != OdometryModel::kGyro) return;
  std::printf(
      "gyro bias of this run: %+.4f deg/s (walk: +-%.4f deg/s over %zu segments of %.0f s): not "
      "written, a gyro's bias belongs to the run and is estimated in every run\n",
      fit.gyro_bias_mean_radps * kDegPerRad, fit.gyro_bias_spread_radps * kDegPerRad,
      fit.gyro_bias_segments.size(), config.gyro_bias_segment_s);
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
  cmd->add_option(
         "--base", opts->base,
         "Kind of base. gyro: heading from a yaw gyro (a Kobuki's /odom), the distance and "
         "turn scales are the robot's, the gyro's bias is the run's (reported, not "
         "written); wheel: heading from the wheels, also a heading drift per metre; "
         "auto: detected from the run (residuals of both, then standstills, then "
         "backend.odometry_model)")
      ->check(CLI::IsMember({"auto", "gyro", "wheel"}))
      ->capture_default_str();
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
    if (opts->base != "auto") {
      OdometryModel base = OdometryModel::kGyro;
      EnumFromName(opts->base, &base);
      options.base = base;
    }
    const slam::CalibrateJobResult result = slam::RunCalibrateJob(config, options);
    const CalibrationFit& fit = result.fit;
    const std::string& yaml = result.yaml;
    // -q: only the result, the configuration keys, and only when no file receives them.
    if (globals.quiet) {
      if (opts->out.empty()) std::printf("%s", yaml.c_str());
      return;
    }
    PrintFit(fit, config.backend);
    std::printf("\n%s", yaml.c_str());
    if (!opts->out.empty()) std::printf("wrote %s\n", opts->out.c_str());
  });
}

}  // namespace uwbsar::tools
