// Measuring a base's odometry calibration once, from a run with ground truth (motion capture,
// a surveyed path, the simulator): the three intrinsics of backend/odometry_calibration.h
// fitted to the truth over segments of the run. The result is what
// backend.calibration_*_mean expects; it matters most for the distance scale, which nothing on
// a mapping tour observes (a ring scaled by any factor still closes).
//
// The run is cut into segments of about `segment_m` of odometry path (or 1 rad of turn). For
// each, the odometry's increments, each corrected by the calibration (CorrectOdometryStep at
// the odometry's own rate) and composed, are compared with the true step (ground truth
// interpolated at the odometry's stamps): one SE(2) residual, weighted like an odometry edge
// (information / path). An intrinsic the run cannot observe (the rotation scale on a straight
// run: less than 3x the backend prior's information on it) keeps the prior's mean and is
// reported as not observed; the others are the least-squares solution, no prior pulling them.
#pragma once

#include <array>
#include <string>
#include <vector>

#include "backend/odometry_calibration.h"
#include "slam/config.h"
#include "slam/types.h"

namespace uwbsar {

struct CalibrationFitOptions {
  double segment_m = 0.5;        ///< odometry path per segment
  double max_truth_gap_s = 0.1;  ///< odometry stamps farther than this from a truth sample on
                                 ///< either side are skipped (the segment restarts)
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
};

/// Fits the calibration of `odometry` against `ground_truth` (both in stamp order, each in its
/// own world frame). Throws InputError when fewer than 10 segments overlap the truth, naming
/// how many there were.
CalibrationFit FitOdometryCalibration(const std::vector<OdometrySample>& odometry,
                                      const std::vector<OdometrySample>& ground_truth,
                                      const BackendConfig& priors,
                                      const CalibrationFitOptions& options = {});

}  // namespace uwbsar
