#include "backend/backend_config.h"

#include <array>
#include <cmath>
#include <string>

#include "core/config_require.h"

namespace uwbsar {

using config_validation::Require;

void Validate(const BackendConfig& b, const std::string& src) {
  Require(b.robust_loss_scale > 0, src, "backend.robust_loss_scale", "must be > 0");
  Require(b.loop_rejection_chi2 > 0, src, "backend.loop_rejection_chi2", "must be > 0");
  Require(b.max_rejection_rounds >= 0, src, "backend.max_rejection_rounds", "must be >= 0");
  Require(b.min_loop_support >= 0, src, "backend.min_loop_support", "must be >= 0");
  Require(b.max_odometry_chi2 >= 0, src, "backend.max_odometry_chi2", "must be >= 0 (0 = off)");
  Require(b.loop_support_window >= 1, src, "backend.loop_support_window", "must be >= 1");
  Require(b.unsupported_loop_chi2 > 0, src, "backend.unsupported_loop_chi2", "must be > 0");
  Require(b.odometry_xy_information > 0, src, "backend.odometry_xy_information", "must be > 0");
  Require(b.odometry_yaw_information > 0, src, "backend.odometry_yaw_information", "must be > 0");
  Require(b.odometry_min_distance_m > 0, src, "backend.odometry_min_distance_m", "must be > 0");
  Require(b.gyro_bias_sigma_dps > 0 && b.gyro_bias_sigma_dps < 10, src,
          "backend.gyro_bias_sigma_dps", "must be in (0, 10)");
  Require(b.gyro_bias_walk_dps_per_sqrt_s >= 0 && b.gyro_bias_walk_dps_per_sqrt_s < 1, src,
          "backend.gyro_bias_walk_dps_per_sqrt_s", "must be in [0, 1) (0: a constant bias)");
  Require(b.gyro_bias_segment_s >= 1, src, "backend.gyro_bias_segment_s", "must be >= 1");
  Require(b.gyro_rate_noise_dps_per_sqrt_hz > 0 && b.gyro_rate_noise_dps_per_sqrt_hz < 10, src,
          "backend.gyro_rate_noise_dps_per_sqrt_hz", "must be in (0, 10)");
  Require(b.gyro_still_min_s > 0, src, "backend.gyro_still_min_s", "must be > 0");
  // A heading drift per metre is a wheel-only base's. On a gyro base it was a run's bias at that
  // run's speed, and applied to another run (whose bias may have the other sign) it made the
  // odometry worse than none.
  Require(b.odometry_model == OdometryModel::kWheel ||
              b.calibration_heading_drift_mean_rad_per_m == 0.0,
          src, "backend.calibration_heading_drift_mean_rad_per_m",
          "must be 0 with backend.odometry_model gyro: a gyro's heading error is the run's bias, "
          "estimated in each run (remove the key, or set odometry_model: wheel for a wheel-only "
          "base)");
  Require(b.calibration_scale_sigma > 0, src, "backend.calibration_scale_sigma", "must be > 0");
  Require(b.calibration_heading_drift_sigma_rad_per_m > 0, src,
          "backend.calibration_heading_drift_sigma_rad_per_m", "must be > 0");
  Require(b.calibration_rotation_sigma > 0, src, "backend.calibration_rotation_sigma",
          "must be > 0");
  Require(b.landmark_right_angle_std_deg >= 0, src, "backend.landmark_right_angle_std_deg",
          "must be >= 0 (0 = off)");
  Require(b.landmark_right_angle_gate_deg > 0 && b.landmark_right_angle_gate_deg < 45, src,
          "backend.landmark_right_angle_gate_deg", "must be in (0, 45)");
  Require(b.landmark_right_angle_max_spread_deg >= 0, src,
          "backend.landmark_right_angle_max_spread_deg", "must be >= 0");
  Require(b.landmark_right_angle_pairs >= 1, src, "backend.landmark_right_angle_pairs",
          "must be >= 1");
  // A base off by more than 20 % (distance or turns) or 0.1 rad per metre needs mending, not
  // a calibration: beyond that a typo (a percentage for a fraction) would pass silently.
  Require(std::abs(b.calibration_scale_mean) <= kMaxCalibrationScale, src,
          "backend.calibration_scale_mean",
          "must be in [-0.2, 0.2] (a fraction: -0.005 for a base over-reporting 0.5 %)");
  Require(
      std::abs(b.calibration_heading_drift_mean_rad_per_m) <= kMaxCalibrationHeadingDriftRadPerM,
      src, "backend.calibration_heading_drift_mean_rad_per_m", "must be in [-0.1, 0.1]");
  Require(std::abs(b.calibration_rotation_mean) <= kMaxCalibrationRotation, src,
          "backend.calibration_rotation_mean", "must be in [-0.2, 0.2] (a fraction)");
  const std::array<double, 3> mean = b.CalibrationMean();
  Require(b.odometry_calibration || mean == std::array<double, 3>{0.0, 0.0, 0.0}, src,
          "backend.odometry_calibration",
          "must be true when a calibration is given (calibration_*_mean): it applies it");
  Require(b.trial_loop_chi2 > 0, src, "backend.trial_loop_chi2", "must be > 0");
  Require(b.max_trial_solves >= 0, src, "backend.max_trial_solves", "must be >= 0 (0 = off)");
  Require(b.loop_xy_information > 0, src, "backend.loop_xy_information", "must be > 0");
  Require(b.loop_yaw_information > 0, src, "backend.loop_yaw_information", "must be > 0");
  Require(b.max_iterations >= 1, src, "backend.max_iterations", "must be >= 1");
  Require(b.function_tolerance > 0 && b.function_tolerance < 1, src, "backend.function_tolerance",
          "must be in (0, 1)");
  Require(b.num_threads >= 1, src, "backend.num_threads", "must be >= 1");
}

}  // namespace uwbsar
