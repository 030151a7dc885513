// Configuration structs. Every field has an in-class default equal to the
// paper's value (or the reference code's where the paper is silent), and a
// Visit() that lists the fields by their YAML key so that one generic loader
// (slam/config_io.h) reads, checks and writes them all. The sections owned by higher
// folders (simulator, live, dds, compare, session) live beside their code and join these
// in the whole file's struct, pipeline/app_config.h.
// config/default.yaml documents every field; a test keeps the two in sync.
#pragma once

#include <array>
#include <string>
#include <vector>

#include "slam/named_enum.h"
#include "slam/place_recognition_config.h"

namespace uwbsar {

/// Transmitted pulse and receiver sampling (paper Table I).
struct PulseConfig {
  double center_frequency_hz = 7.29e9;  ///< fc
  double bandwidth_hz = 1.4e9;          ///< -6 dB bandwidth (reference code; paper table: 2 GHz)
  double sampling_frequency_hz = 23.328e9;  ///< fs; one range bin = c / (2 fs)
  double amplitude_v = 0.6;                 ///< pulse amplitude (reference code; paper: 1.0 V)

  template <class V>
  void Visit(V& v) {
    v("center_frequency_hz", center_frequency_hz);
    v("bandwidth_hz", bandwidth_hz);
    v("sampling_frequency_hz", sampling_frequency_hz);
    v("amplitude_v", amplitude_v);
  }
};
/// Semantic checks of pulse.*; throws ConfigError naming the dotted key.
void Validate(const PulseConfig& config, const std::string& source_name);

/// One radar: where it sits on the robot, where it looks, what it sees.
struct RadarConfig {
  std::string name = "left";                  ///< label used in logs and outputs
  std::string topic = "/UWBradar0/readings";  ///< bag / ROS 2 topic of its scans
  double mount_x_m = 0.0;                     ///< antenna position in the robot frame (x forward)
  double mount_y_m = 0.18;                    ///< antenna position in the robot frame (y left)
  double boresight_yaw_deg = 90.0;            ///< boresight direction in the robot frame
  double fov_half_angle_deg = 30.0;           ///< half of the effective beam width
  double min_range_m = 0.4;                   ///< pixels closer than this are not imaged
  double max_range_m = 3.0;                   ///< pixels farther than this are not imaged
  double range_offset_m = 0.0;                ///< range of sample 0 (cable/antenna delay)
  int num_samples = 1000;                     ///< expected samples per scan
  int zero_leading_samples = 1;               ///< samples zeroed before use (reference zeroes 1)

  template <class V>
  void Visit(V& v) {
    v("name", name);
    v("topic", topic);
    v("mount_x_m", mount_x_m);
    v("mount_y_m", mount_y_m);
    v("boresight_yaw_deg", boresight_yaw_deg);
    v("fov_half_angle_deg", fov_half_angle_deg);
    v("min_range_m", min_range_m);
    v("max_range_m", max_range_m);
    v("range_offset_m", range_offset_m);
    v("num_samples", num_samples);
    v("zero_leading_samples", zero_leading_samples);
  }
};

/// The paper's robot: left radar looks to +90 deg, right radar to -90 deg.
inline std::vector<RadarConfig> DefaultRadars() {
  RadarConfig left;
  RadarConfig right;
  right.name = "right";
  right.topic = "/UWBradar1/readings";
  right.mount_y_m = -0.18;
  right.boresight_yaw_deg = -90.0;
  return {left, right};
}
/// Semantic checks of radars[*]; throws ConfigError naming the dotted key.
void Validate(const std::vector<RadarConfig>& radars, const std::string& source_name);

/// imaging.mode: "paper": real samples, linear interpolation (as the paper); "coherent":
/// analytic signal with exp(j 4 pi fc R / c) phase.
enum class ImagingMode { kPaper, kCoherent };
template <>
struct EnumNames<ImagingMode> {
  static constexpr std::pair<ImagingMode, const char*> kNames[] = {
      {ImagingMode::kPaper, "paper"}, {ImagingMode::kCoherent, "coherent"}};
};

/// Back-projection (paper section "Back-projection Algorithm").
struct ImagingConfig {
  ImagingMode mode = ImagingMode::kPaper;  ///< paper or coherent (see ImagingMode)
  double pixel_size_m = 0.005;             ///< 5 mm per pixel, as the paper
  int coherent_oversampling = 4;  ///< analytic-signal upsampling before interpolation (coherent)
  int num_threads = 2;            ///< threads for back-projection (0 = OpenCV default)

  bool coherent() const { return mode == ImagingMode::kCoherent; }

  template <class V>
  void Visit(V& v) {
    v("mode", mode);
    v("pixel_size_m", pixel_size_m);
    v("coherent_oversampling", coherent_oversampling);
    v("num_threads", num_threads);
  }
};
/// Semantic checks of imaging.*; throws ConfigError naming the dotted key.
void Validate(const ImagingConfig& config, const std::string& source_name);

/// Scan gating and odometry sanity checks.
struct GatingConfig {
  double min_travel_m = 0.003;   ///< accept a scan after this much robot travel (paper: 3 mm)
  double max_odom_jump_m = 0.5;  ///< a larger step between consecutive odometry samples is rejected
  double max_odom_gap_s = 0.5;   ///< scans farther than this from odometry samples are rejected
  double max_scan_latency_s = 1.0;   ///< scans waiting longer than this for odometry are dropped
  double max_odom_speed_mps = 10.0;  ///< a step implying a faster speed is an outlier or a reset
  double max_odom_turn_rate_radps = 12.0;  ///< a step implying a faster turn likewise

  template <class V>
  void Visit(V& v) {
    v("min_travel_m", min_travel_m);
    v("max_odom_jump_m", max_odom_jump_m);
    v("max_odom_gap_s", max_odom_gap_s);
    v("max_scan_latency_s", max_scan_latency_s);
    v("max_odom_speed_mps", max_odom_speed_mps);
    v("max_odom_turn_rate_radps", max_odom_turn_rate_radps);
  }
};
/// Semantic checks of gating.*; throws ConfigError naming the dotted key.
void Validate(const GatingConfig& config, const std::string& source_name);

/// Keyframe tiles: overlapping SAR images of L metres of path (the paper's regions).
struct KeyframeConfig {
  double tile_length_m = 2.0;   ///< path length imaged into one tile (paper: 400 px = 2 m)
  double tile_spacing_m = 1.0;  ///< path between tile starts (paper: 1 m step); tile_length_m
                                ///< must be a whole multiple of it
  double margin_m = 0.25;       ///< extra border around the sensors' reach, in the anchor frame

  template <class V>
  void Visit(V& v) {
    v("tile_length_m", tile_length_m);
    v("tile_spacing_m", tile_spacing_m);
    v("margin_m", margin_m);
  }
};
/// Semantic checks of keyframe.*; throws ConfigError naming the dotted key.
void Validate(const KeyframeConfig& config, const std::string& source_name);

/// Image enhancement for display and features (paper section "UWB SAR Imaging").
struct EnhanceConfig {
  double blur_sigma_px = 2.0;        ///< Gaussian blur of the positive image
  double display_range_db = 30.0;    ///< dynamic range of log-magnitude display (coherent)
  std::string colormap = "inferno";  ///< PNG colour map: gray, inferno, jet, viridis, magma, hot

  template <class V>
  void Visit(V& v) {
    v("blur_sigma_px", blur_sigma_px);
    v("display_range_db", display_range_db);
    v("colormap", colormap);
  }
};
/// Semantic checks of enhance.*; throws ConfigError naming the dotted key.
void Validate(const EnhanceConfig& config, const std::string& source_name);

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
    v("calibration_scale_sigma", calibration_scale_sigma);
    v("calibration_heading_drift_sigma_rad_per_m", calibration_heading_drift_sigma_rad_per_m);
    v("calibration_rotation_sigma", calibration_rotation_sigma);
    v("calibration_scale_mean", calibration_scale_mean);
    v("calibration_heading_drift_mean_rad_per_m", calibration_heading_drift_mean_rad_per_m);
    v("calibration_rotation_mean", calibration_rotation_mean);
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

/// The SLAM pipeline as `uwbsar map` and live mode run it.
struct SlamConfig {
  std::string odometry_topic = "/odom";  ///< nav_msgs/Odometry topic of wheel odometry
  std::string ground_truth_topic = "/ground_truth/odom";  ///< optional, for evaluation
  double map_resolution_m = 0.01;    ///< pixel size of the global map (map.png, map_float.tif)
  bool keep_tile_images = false;     ///< keep every full-resolution tile in memory after its
                                     ///< features are computed (debugging; costs ~5 MB per metre)
  bool keep_scan_profiles = false;   ///< keep every imaged scan's range profile (0.8 MB per
                                     ///< metre) for the exact map; `uwbsar map --exact` sets it
  int optimize_every_keyframes = 5;  ///< re-solve the graph once this many keyframes have
                                     ///< come since the last solve and a loop is waiting
                                     ///< (1: after every loop; 0: only at the end, like the
                                     ///< follow-on code). Bounds the solver's share of a long run
  bool keyframe_thread = true;       ///< keyframe work (features, matching, solves) on its own
                                     ///< thread, so scan imaging never waits for it; the result
                                     ///< is the same either way (false: all on the caller's thread)
  int keyframe_queue_size = 16;      ///< keyframes waiting for that thread; when full, the
                                     ///< feeding thread waits (bounds memory in offline runs)
  double occupancy_resolution_m = 0.05;  ///< cell size of map.pgm (map_server format)
  double occupied_fraction = 0.6;        ///< a cell is occupied when its strongest map pixel
                                         ///< reaches this fraction of the reference level
                                         ///< (0.6: best F1 of the paper's real strip vs
                                         ///< LiDAR; 0.3, tuned on simulated maps, made
                                         ///< real clutter occupied)
  double occupancy_reference_percentile = 99.0;  ///< reference level: this percentile of
                                                 ///< the observed map pixels

  template <class V>
  void Visit(V& v) {
    v("odometry_topic", odometry_topic);
    v("ground_truth_topic", ground_truth_topic);
    v("map_resolution_m", map_resolution_m);
    v("keep_tile_images", keep_tile_images);
    v("keep_scan_profiles", keep_scan_profiles);
    v("optimize_every_keyframes", optimize_every_keyframes);
    v("keyframe_thread", keyframe_thread);
    v("keyframe_queue_size", keyframe_queue_size);
    v("occupancy_resolution_m", occupancy_resolution_m);
    v("occupied_fraction", occupied_fraction);
    v("occupancy_reference_percentile", occupancy_reference_percentile);
  }
};
/// Semantic checks of slam.* (the rules joining it to radars[] are in ValidateCoreConfig); throws
/// ConfigError naming the dotted key.
void Validate(const SlamConfig& config, const std::string& source_name);

/// Budgets on the sizes the other settings imply (README "What uwbsar refuses"): the
/// configuration is refused before any work starts when a setting would exceed them, and
/// input files declaring larger images are refused before they are decoded.
struct LimitsConfig {
  double max_tile_pixels = 3.2e7;         ///< one keyframe image: the segment canvas at
                                          ///< imaging.pixel_size_m, a tile's footprint at
                                          ///< slam.map_resolution_m (defaults: 3.2e6 and 1.0e6)
  double max_imaging_memory_mb = 2048.0;  ///< segment canvases alive at once (tile_length_m /
                                          ///< tile_spacing_m + 1) x canvas bytes (default 39)
  double max_keyframes_per_m = 20.0;      ///< 1 / keyframe.tile_spacing_m (default 1)
  double max_range_samples = 1.0e6;     ///< radars[].num_samples x coherent_oversampling (coherent)
  double max_image_pixels = 2.0e8;      ///< a whole-run image: `image` strips, `map --exact`
  double max_map_image_pixels = 5.0e7;  ///< declared size of an image read from a file (map_server
                                        ///< maps for simulate / compare / export-pcd, float maps)

  template <class V>
  void Visit(V& v) {
    v("max_tile_pixels", max_tile_pixels);
    v("max_imaging_memory_mb", max_imaging_memory_mb);
    v("max_keyframes_per_m", max_keyframes_per_m);
    v("max_range_samples", max_range_samples);
    v("max_image_pixels", max_image_pixels);
    v("max_map_image_pixels", max_map_image_pixels);
  }
};

/// The core sections: what drivers, frontend, backend and session code may be given (each
/// module takes only its own sections). The whole file's struct, `Config`
/// (pipeline/app_config.h), adds the sections owned by higher folders (simulator, live,
/// dds, compare, session); its Visit lists every section in the file's order.
struct CoreConfig {
  PulseConfig pulse;
  std::vector<RadarConfig> radars = DefaultRadars();
  ImagingConfig imaging;
  GatingConfig gating;
  KeyframeConfig keyframe;
  EnhanceConfig enhance;
  BackendConfig backend;
  PlaceRecognitionConfig place_recognition;

  SlamConfig slam;
  LimitsConfig limits;

  template <class V>
  void Visit(V& v) {
    v("slam", slam);
    v("pulse", pulse);
    v("radars", radars);
    v("imaging", imaging);
    v("gating", gating);
    v("keyframe", keyframe);
    v("enhance", enhance);
    v("backend", backend);
    v("place_recognition", place_recognition);
    v("limits", limits);
  }
};

}  // namespace uwbsar
