// Settings of backend.*, declared beside the code that owns them (backend/pose_graph.h); the
// application configuration (slam/config/system_config.h, slam/app_config.h) assembles the
// sections, and core/config_io.h reads and writes any struct with a Visit(). config/default.yaml
// documents every field; a test keeps the two in sync.
#pragma once

#include <array>
#include <string>

#include "core/named_enum.h"

namespace uwbsar {

/// backend.initialization: the first solve starts from the nodes' initial estimates
/// (guess) or from a chordal relaxation (chordal).
enum class GraphInitialization { kGuess, kChordal };
template <>
struct EnumNames<GraphInitialization> {
  static constexpr std::pair<GraphInitialization, const char*> kNames[] = {
      {GraphInitialization::kGuess, "guess"}, {GraphInitialization::kChordal, "chordal"}};
};

/// backend.robust_loss: the loss on loop edges while outliers are sought.
enum class RobustLoss { kCauchy, kHuber, kNone };
template <>
struct EnumNames<RobustLoss> {
  static constexpr std::pair<RobustLoss, const char*> kNames[] = {
      {RobustLoss::kCauchy, "cauchy"}, {RobustLoss::kHuber, "huber"}, {RobustLoss::kNone, "none"}};
};

/// backend.odometry_model: how the base's odometry errs (backend/odometry_calibration.h).
/// gyro: heading from a yaw gyro (the Kobuki's kobuki_node default): the turns' scale belongs to
/// the robot, the bias to the run (backend/gyro_bias_track.h). wheel: heading from the wheels:
/// a heading drift per metre (unequal wheel radii) belongs to the robot.
enum class OdometryModel { kGyro, kWheel };
template <>
struct EnumNames<OdometryModel> {
  static constexpr std::pair<OdometryModel, const char*> kNames[] = {
      {OdometryModel::kGyro, "gyro"}, {OdometryModel::kWheel, "wheel"}};
};

/// The largest calibration backend.calibration_*_mean accept (config validation), and the
/// largest `uwbsar calibrate` reports: a base off by more than 20 % (distance or turns) or
/// 0.1 rad per metre needs mending, not a calibration.
constexpr double kMaxCalibrationScale = 0.2;
constexpr double kMaxCalibrationHeadingDriftRadPerM = 0.1;
constexpr double kMaxCalibrationRotation = 0.2;

/// Pose-graph backend (Ceres): loop outlier handling, odometry weighting, solver settings.
struct BackendConfig {
  GraphInitialization initialization = GraphInitialization::kGuess;  ///< guess or chordal
  RobustLoss robust_loss = RobustLoss::kCauchy;  ///< cauchy, huber or none (on loop edges)
  double robust_loss_scale = 2.0;       ///< whitened residual norm (sigmas) where it turns robust
  double loop_rejection_chi2 = 16.27;   ///< a loop whose chi2 at the solution exceeds this is
                                        ///< rejected (16.27 = 99.9 % quantile, 3 DOF)
  int max_rejection_rounds = 10;        ///< solve / reject / re-admit rounds per optimisation
  int min_loop_support = 1;             ///< loops agreeing with fewer other loops nearby are
                                        ///< held back and only admitted if the map solved
                                        ///< without them confirms them; 0 disables
  int loop_support_window = 10;         ///< nodes along the odometry chain that count as nearby
  double unsupported_loop_chi2 = 32.5;  ///< a held-back loop is admitted when its chi2 against
                                        ///< the map solved without it is at most this (twice
                                        ///< loop_rejection_chi2: the map's own uncertainty
                                        ///< between the ends counted as one more loop)
  bool final_least_squares = true;      ///< last solve without loss on the accepted loops
  double max_odometry_chi2 = 30.0;      ///< after a solve, an odometry edge above this chi2
                                        ///< gets a loop spanning it rejected (0 = off;
                                        ///< 30 = 1e-6 tail of chi2, 3 DOF)
  double odometry_xy_information = 2500.0;    ///< x, y information of 1 m of odometry (1/m^2):
                                              ///< sigma 2 cm per metre (wheel odometry, 1-2 %),
                                              ///< divided by the edge's travelled distance
  double odometry_yaw_information = 10000.0;  ///< yaw information of 1 m of odometry (1/rad^2):
                                              ///< sigma 0.6 deg per metre
  double odometry_min_distance_m = 0.1;       ///< shorter odometry edges weigh as this distance
  bool odometry_calibration = true;  ///< estimate each trajectory's odometry intrinsics (distance
                                     ///< scale, heading drift per metre, rotation scale) while
                                     ///< loops constrain them (backend/odometry_calibration.h)
  OdometryModel odometry_model = OdometryModel::kGyro;  ///< gyro or wheel (see the enum)
  double gyro_bias_sigma_dps = 0.03;  ///< gyro: spread of the turn-on bias, the prior of a run's
                                      ///< bias before standstills and loops observe it
  double gyro_bias_walk_dps_per_sqrt_s = 0.0005;  ///< gyro: the bias's random walk (0: constant)
  double gyro_bias_segment_s = 30.0;  ///< gyro: the bias is estimated per this much time
  double gyro_rate_noise_dps_per_sqrt_hz = 0.03;  ///< gyro: white rate noise (standstills'
                                                  ///< measurement of the bias)
  double gyro_still_min_s = 0.5;  ///< gyro: a standstill this long or longer measures the bias
  double calibration_scale_sigma = 0.02;  ///< prior sigma of the distance scale (fraction)
  double calibration_heading_drift_sigma_rad_per_m = 0.005;  ///< prior sigma of the heading
                                                             ///< drift per metre travelled
  double calibration_rotation_sigma = 0.05;  ///< prior sigma of the rotation scale (fraction);
                                             ///< wall edges tell it from the heading drift (set
                                             ///< 0.001 without them: a ring cannot)
  /// The base's measured odometry calibration, the prior's mean (all 0: uncalibrated). Nothing
  /// on a tour observes the distance scale, so the map's scale is this one's.
  double calibration_scale_mean = 0.0;  ///< distances are multiplied by (1 + this)
  double calibration_heading_drift_mean_rad_per_m = 0.0;  ///< heading lost per metre
  double calibration_rotation_mean = 0.0;                 ///< turns are multiplied by (1 + this)
  /// Right angles between wall landmarks (buildings are mostly rectilinear): each new landmark
  /// is a candidate with each of the last landmark_right_angle_pairs landmarks before it. A
  /// candidate is decided once, at the first solve where an accepted loop encloses it (its older
  /// node no later than the first node seeing either wall, its newer node no earlier than the
  /// last): when the solved angles then differ by a whole number of quarter turns within
  /// landmark_right_angle_gate_deg, the pair gets a robust prior (the loops' loss) holding that
  /// difference with this standard deviation (0 = off). Before the loop, the heading drift and
  /// turn scale between the walls are not yet solved. No pair is held in a building that is not
  /// rectilinear: decided once, when loops first enclose at least 4 walls, from their rms
  /// departure from one rectilinear frame (backend/rectilinear_frame.h; each wall weighted by
  /// the keyframes that see it), which must be within landmark_right_angle_max_spread_deg.
  double landmark_right_angle_std_deg = 0.5;
  double landmark_right_angle_gate_deg = 1.0;
  double landmark_right_angle_max_spread_deg = 0.75;
  int landmark_right_angle_pairs = 8;
  int max_trial_solves = 2;  ///< loops still held back as unsupported, tried per Optimize() in a
                             ///< solve of their own (lowest chi2 first, each once); 0 = off
  double trial_loop_chi2 = 16.27;      ///< trial: the most the solution's chi2 (all edges and
                                       ///< calibration priors) may grow by the loop
  double loop_xy_information = 44.7;   ///< loop information when none is given (follow-on)
  double loop_yaw_information = 44.7;  ///< loop yaw information when none is given (follow-on)
  int max_iterations = 100;            ///< Ceres iterations per solve
  double function_tolerance = 1e-10;   ///< Ceres convergence: relative change of the cost
  int num_threads = 1;                 ///< Ceres threads (Jacobian evaluation)

  template <class V>
  void Visit(V& v) {
    v("initialization", initialization);
    v("robust_loss", robust_loss);
    v("robust_loss_scale", robust_loss_scale);
    v("loop_rejection_chi2", loop_rejection_chi2);
    v("max_rejection_rounds", max_rejection_rounds);
    v("min_loop_support", min_loop_support);
    v("loop_support_window", loop_support_window);
    v("unsupported_loop_chi2", unsupported_loop_chi2);
    v("final_least_squares", final_least_squares);
    v("max_odometry_chi2", max_odometry_chi2);
    v("odometry_xy_information", odometry_xy_information);
    v("odometry_yaw_information", odometry_yaw_information);
    v("odometry_min_distance_m", odometry_min_distance_m);
    v("odometry_calibration", odometry_calibration);
    v("odometry_model", odometry_model);
    v("gyro_bias_sigma_dps", gyro_bias_sigma_dps);
    v("gyro_bias_walk_dps_per_sqrt_s", gyro_bias_walk_dps_per_sqrt_s);
    v("gyro_bias_segment_s", gyro_bias_segment_s);
    v("gyro_rate_noise_dps_per_sqrt_hz", gyro_rate_noise_dps_per_sqrt_hz);
    v("gyro_still_min_s", gyro_still_min_s);
    v("calibration_scale_sigma", calibration_scale_sigma);
    v("calibration_heading_drift_sigma_rad_per_m", calibration_heading_drift_sigma_rad_per_m);
    v("calibration_rotation_sigma", calibration_rotation_sigma);
    v("calibration_scale_mean", calibration_scale_mean);
    v("calibration_heading_drift_mean_rad_per_m", calibration_heading_drift_mean_rad_per_m);
    v("calibration_rotation_mean", calibration_rotation_mean);
    v("landmark_right_angle_std_deg", landmark_right_angle_std_deg);
    v("landmark_right_angle_gate_deg", landmark_right_angle_gate_deg);
    v("landmark_right_angle_max_spread_deg", landmark_right_angle_max_spread_deg);
    v("landmark_right_angle_pairs", landmark_right_angle_pairs);
    v("max_trial_solves", max_trial_solves);
    v("trial_loop_chi2", trial_loop_chi2);
    v("loop_xy_information", loop_xy_information);
    v("loop_yaw_information", loop_yaw_information);
    v("max_iterations", max_iterations);
    v("function_tolerance", function_tolerance);
    v("num_threads", num_threads);
  }

  /// The calibration means as [scale, heading drift, rotation] (backend/odometry_calibration.h).
  std::array<double, 3> CalibrationMean() const {
    return {calibration_scale_mean, calibration_heading_drift_mean_rad_per_m,
            calibration_rotation_mean};
  }
};
/// Semantic checks of backend.*; throws ConfigError naming the dotted key.
void Validate(const BackendConfig& config, const std::string& source_name);

}  // namespace uwbsar
