// `uwbsar calibrate BAG [--ground-truth TUM] [--segment-m M] [--out FILE.yaml]`: measures the
// base's odometry calibration once, on a run with ground truth (motion capture, a surveyed
// path, the simulator's topic), and prints it as the backend.calibration_*_mean keys
// (backend/odometry_calibration_fit.h). --out writes them as a configuration file.
#include <cmath>
#include <cstdio>
#include <sstream>

#include "backend/odometry_calibration_fit.h"
#include "drivers/logs/tum_reader.h"
#include "drivers/rosbag/robot_bag.h"
#include "imaging/image_io.h"
#include "tools/commands.h"

namespace uwbsar::tools {
namespace {

struct CalibrateOptions {
  std::string bag, ground_truth, out;
  double segment_m = 0.5;
};

/// Keeps the odometry and the ground truth of a bag.
class OdometryAndTruth : public rosbag::RobotBagVisitor {
 public:
  void OnOdometry(const OdometrySample& o) override { odometry.push_back(o); }
  void OnGroundTruth(const OdometrySample& p) override { ground_truth.push_back(p); }
  std::vector<OdometrySample> odometry, ground_truth;
};

/// The backend keys of the fit. The scale's prior sigma: the fit's 3-sigma, at least 0.001
/// (a base's calibration wanders with load and tyres by about that much).
std::string CalibrationYaml(const CalibrationFit& fit) {
  std::ostringstream y;
  y.precision(6);
  y << "# uwbsar calibrate: " << fit.segments << " segments, " << fit.path_m << " m\n"
    << "backend:\n"
    << "  calibration_scale_mean: " << fit.calibration[kCalibScale] << "\n"
    << "  calibration_heading_drift_mean_rad_per_m: " << fit.calibration[kCalibHeadingDrift] << "\n"
    << "  calibration_rotation_mean: " << fit.calibration[kCalibRotation] << "\n";
  if (fit.observed[kCalibScale]) {
    y << "  calibration_scale_sigma: " << std::max(0.001, 3.0 * fit.sigma[kCalibScale]) << "\n";
  }
  return y.str();
}

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
      ->check(CLI::ExistingFile);
  cmd->add_option("--segment-m", opts->segment_m, "Odometry path per fitted segment")
      ->check(CheckPositiveFinite);
  cmd->add_option("--out", opts->out, "Write the calibration as a configuration file (YAML)");
  cmd->callback([opts, &globals] {
    const Config config = LoadConfigFor(globals);
    if (!opts->out.empty()) pipeline::CheckOutputFile(opts->out);  // before the work
    OdometryAndTruth streams;
    rosbag::ReadRobotBag(opts->bag, rosbag::RobotBagOptionsFromConfig(config), streams);
    if (!opts->ground_truth.empty()) streams.ground_truth = ReadTum(opts->ground_truth);
    if (streams.ground_truth.empty()) {
      throw InputError(opts->bag + ": no ground truth (topic " + config.slam.ground_truth_topic +
                       "); give one with --ground-truth");
    }
    CalibrationFitOptions fit_options;
    fit_options.segment_m = opts->segment_m;
    fit_options.max_step_m = config.gating.max_odom_jump_m;
    fit_options.max_speed_mps = config.gating.max_odom_speed_mps;
    fit_options.max_turn_rate_radps = config.gating.max_odom_turn_rate_radps;
    fit_options.odometry_source = opts->bag;
    fit_options.truth_source = opts->ground_truth.empty()
                                   ? opts->bag + " (" + config.slam.ground_truth_topic + ")"
                                   : opts->ground_truth;
    const CalibrationFit fit =
        FitOdometryCalibration(streams.odometry, streams.ground_truth, config.backend, fit_options);
    const std::string yaml = CalibrationYaml(fit);
    if (!opts->out.empty()) WriteTextAtomic(opts->out, yaml);
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
