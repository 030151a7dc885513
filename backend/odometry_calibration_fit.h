// Measuring a base's odometry calibration once, from a run with ground truth (motion capture,
// a surveyed path, the simulator): the three intrinsics of backend/odometry_calibration.h
// fitted to the truth over segments of the run. The result is what
// backend.calibration_*_mean expects; it matters most for the distance scale, which nothing on
// a mapping tour observes (a ring scaled by any factor still closes).
//
// The run is cut into segments of about `segment_m` of odometry path (or 1 rad of turn;
// backend/odometry_calibration_segments.h). For each, the odometry's increments, each
// corrected by the calibration (CorrectOdometryStep at the odometry's own rate) and composed,
// are compared with the true step (ground truth interpolated at the odometry's stamps): one
// SE(2) residual, weighted like an odometry edge (information / path). An intrinsic the run cannot
// observe (the rotation scale on a straight run: less than 3x the backend prior's information on
// it) keeps the prior's mean and is reported as not observed; the others are the least-squares
// solution, no prior pulling them.
//
// Which intrinsics belong to the robot depends on its kind of base (backend.odometry_model):
//  - wheel: the distance scale, the heading drift per metre and the turns' scale;
//  - gyro: the distance scale and the turns' scale. Its heading error is the gyro's bias, in
//    rad/s over time (standstills included), set at each power-up and wandering: it is fitted
//    per gyro_bias_segment_s of the run and reported, but it belongs to the run, and the drift
//    per metre is held at 0.
// Unless told, the kind is detected: both models are fitted with one constant each (drift per
// metre, or bias per second; same number of unknowns) and the one whose residuals are clearly
// smaller wins; when they explain the run alike (time and path grow together at a steady
// speed), the standstills decide: a gyro's heading turns while the base stands still, a wheel
// base's does not move; with neither, the configured model.
#pragma once

#include <array>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "backend/backend_config.h"
#include "backend/odometry_calibration.h"
#include "core/types.h"

namespace uwbsar {

struct CalibrationFitOptions {
  double segment_m = 0.5;        ///< odometry path per segment
  double max_truth_gap_s = 0.1;  ///< odometry stamps farther than this from a truth sample on
                                 ///< either side are skipped (the segment restarts)
  /// An odometry step longer than this, or faster than max_speed_mps / max_turn_rate_radps
  /// (and longer than 5 cm or 0.5 rad), is a jump (a reset, two runs in one recording): the
  /// run is refused (gating.max_odom_jump_m, max_odom_speed_mps, max_odom_turn_rate_radps).
  /// So is a ground-truth step the fit interpolates across (a glitch or a reset of the truth).
  double max_step_m = 0.5;
  double max_speed_mps = 10.0;
  double max_turn_rate_radps = 12.0;
  double min_truth_path_m = 1.0;  ///< ground truth moving less over the segments is refused
  /// The odometry's and the truth's path over the segments may differ by this factor at most
  /// (a base's scale error is a few percent; the fit accepts kMaxCalibrationScale).
  double max_path_ratio = 1.5;
  std::string odometry_source = "odometry";   ///< names the odometry in messages
  std::string truth_source = "ground truth";  ///< names the ground truth in messages
  /// The line of truth_source holding each ground-truth sample (a TUM file), to name it in
  /// messages; empty when the truth is not a text file.
  std::vector<int> truth_lines;
  /// The kind of base; none: detected from the run (the file comment).
  std::optional<OdometryModel> model;
};

/// Why the fit chose its model, with the evidence of both tests (filled also when told).
struct CalibrationModelEvidence {
  bool told = false;            ///< CalibrationFitOptions::model was given
  std::string decided_by;       ///< "told", "residuals", "standstills" or "configuration"
  double wheel_chi2 = 0.0;      ///< both models' residuals (one constant each), chi2 in units of
  double gyro_chi2 = 0.0;       ///< the better one's noise per degree of freedom
  double still_s = 0.0;         ///< time the base stood still (backend/gyro_stillness.h)
  double still_turn_rad = 0.0;  ///< |heading change| summed over the standstills
};

struct CalibrationFit {
  OdometryCalibration calibration{};  ///< [scale, heading drift rad/m, rotation]
  std::array<double, 3> sigma{};      ///< standard error of each (scaled by the residuals' chi2)
  std::array<bool, 3> observed{};     ///< the run constrains it (sigma < half the prior sigma)
  int segments = 0;
  double path_m = 0.0;           ///< odometry path over the segments used
  double abs_turn_rad = 0.0;     ///< |turn| summed over the segments
  double xy_rms_before_m = 0.0;  ///< per-segment position error of the raw odometry
  double xy_rms_after_m = 0.0;   ///< ... and of the calibrated odometry
  double yaw_rms_before_rad = 0.0;
  double yaw_rms_after_rad = 0.0;
  /// The model fitted. A gyro's calibration[kCalibHeadingDrift] is 0 and not observed.
  OdometryModel model = OdometryModel::kWheel;
  CalibrationModelEvidence evidence;
  /// Gyro only: the run's bias (rad/s), one per gyro_bias_segment_s of the run that holds
  /// segments (start time from the first odometry sample, bias) and their mean over time.
  std::vector<std::pair<double, double>> gyro_bias_segments;
  double gyro_bias_mean_radps = 0.0;
  double gyro_bias_spread_radps = 0.0;  ///< rms of the segments' biases about the mean
};

/// Fits the calibration of `odometry` against `ground_truth` (both in stamp order, each in its
/// own world frame). Throws InputError (one line naming the source) when the stamps of either
/// go back, either jumps (the ground truth: between samples the fit interpolates across, up to
/// twice max_truth_gap_s apart), fewer than 10 segments overlap the truth (naming how many
/// there were), the truth moves less than min_truth_path_m over them, the two paths differ by
/// more than max_path_ratio, or a fitted value lies outside what backend.calibration_*_mean
/// accept (kMaxCalibration*): a result uwbsar would refuse to load is never returned.
CalibrationFit FitOdometryCalibration(const std::vector<OdometrySample>& odometry,
                                      const std::vector<OdometrySample>& ground_truth,
                                      const BackendConfig& priors,
                                      const CalibrationFitOptions& options = {});

}  // namespace uwbsar
