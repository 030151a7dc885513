// The job behind `uwbsar calibrate`: the base's odometry calibration measured once on a run
// with ground truth (motion capture, a surveyed path, the simulator's topic) by
// backend/odometry_calibration_fit.h, and written as the configuration file that carries it
// (the backend keys that belong to the robot, through the configuration writer of
// core/config_io.h). A gyro's bias belongs to the run: it is reported, never written.
#pragma once

#include <optional>
#include <string>

#include "backend/odometry_calibration_fit.h"
#include "slam/app_config.h"

namespace uwbsar::slam {

struct CalibrateJobOptions {
  std::string bag;                    ///< the run: bag directory, .db3 or .mcap
  std::string ground_truth_tum;       ///< the true poses; empty: the bag's slam.ground_truth_topic
  std::string out_yaml;               ///< write the calibration here; empty: not written
  double segment_m = 0.5;             ///< odometry path per fitted segment
  std::optional<OdometryModel> base;  ///< the kind of base; none: detected from the run
};

struct CalibrateJobResult {
  CalibrationFit fit;
  std::string yaml;  ///< CalibrationYaml(fit), as written to out_yaml
};

/// Checks `out_yaml` (before the work), reads the bag's odometry and ground truth (or the TUM
/// file), fits the calibration with config.backend's priors and config.gating's odometry jump
/// limits, and writes the YAML. Throws InputError when there is no ground truth (naming the
/// topic) or the fit refuses the run; nothing is written then.
CalibrateJobResult RunCalibrateJob(const Config& config, const CalibrateJobOptions& options);

/// The configuration file of a fit: a "# uwbsar calibrate: N segments, P m, gyro base" comment
/// line, then what belongs to the robot: backend.odometry_model (the kind fitted),
/// calibration_scale_mean, calibration_rotation_mean, for a wheel base also
/// calibration_heading_drift_mean_rad_per_m, and, when the run observed the scale,
/// calibration_scale_sigma (the fit's 3-sigma, at least 0.001: a base's calibration wanders
/// with load and tyres by about that much); never a gyro's bias (the run's). Written by the
/// configuration writer with 6 significant digits, keys in the file's order. Loads with
/// `--config`.
std::string CalibrationYaml(const CalibrationFit& fit);

}  // namespace uwbsar::slam
