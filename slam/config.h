// Configuration structs. Every field has an in-class default equal to the
// paper's value (or the reference code's where the paper is silent), and a
// Visit() that lists the fields by their YAML key so that one generic loader
// (slam/config_io.h) reads, checks and writes them all.
// config/default.yaml documents every field; a test keeps the two in sync.
#pragma once

#include <string>
#include <vector>

namespace uwbsar {

/// Transmitted pulse and receiver sampling (paper Table I, REFERENCE.md section 1).
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

/// Back-projection (paper section "Back-projection Algorithm").
struct ImagingConfig {
  std::string mode = "paper";     ///< "paper": real samples, linear interpolation (as the paper);
                                  ///< "coherent": analytic signal with exp(j 4 pi fc R / c) phase
  double pixel_size_m = 0.005;    ///< 5 mm per pixel, as the paper
  int coherent_oversampling = 4;  ///< analytic-signal upsampling before interpolation (coherent)
  int num_threads = 2;            ///< threads for back-projection (0 = OpenCV default)

  template <class V>
  void Visit(V& v) {
    v("mode", mode);
    v("pixel_size_m", pixel_size_m);
    v("coherent_oversampling", coherent_oversampling);
    v("num_threads", num_threads);
  }
};

/// Scan gating and odometry sanity checks.
struct GatingConfig {
  double min_travel_m = 0.003;   ///< accept a scan after this much robot travel (paper: 3 mm)
  double max_odom_jump_m = 0.5;  ///< a larger step between consecutive odometry samples is rejected
  double max_odom_gap_s = 0.5;   ///< scans farther than this from odometry samples are rejected
  double max_scan_latency_s = 1.0;  ///< scans waiting longer than this for odometry are dropped

  template <class V>
  void Visit(V& v) {
    v("min_travel_m", min_travel_m);
    v("max_odom_jump_m", max_odom_jump_m);
    v("max_odom_gap_s", max_odom_gap_s);
    v("max_scan_latency_s", max_scan_latency_s);
  }
};

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

/// Pose-graph backend (Ceres): loop outlier handling, odometry weighting, solver settings.
struct BackendConfig {
  std::string initialization = "guess";  ///< first solve starts from: guess (the nodes'
                                         ///< initial estimates) or chordal (relaxation)
  std::string robust_loss = "cauchy";    ///< loss on loop edges while outliers are sought:
                                         ///< cauchy, huber or none
  double robust_loss_scale = 2.0;        ///< whitened residual norm (sigmas) where it turns robust
  double loop_rejection_chi2 = 16.27;    ///< a loop whose chi2 at the solution exceeds this is
                                         ///< rejected (16.27 = 99.9 % quantile, 3 DOF)
  int max_rejection_rounds = 10;         ///< solve / reject / re-admit rounds per optimisation
  int min_loop_support = 1;              ///< loops agreeing with fewer other loops nearby are
                                         ///< held back and only admitted if the map solved
                                         ///< without them confirms them; 0 disables
  int loop_support_window = 10;          ///< nodes along the odometry chain that count as nearby
  double unsupported_loop_chi2 = 32.5;   ///< a held-back loop is admitted when its chi2 against
                                         ///< the map solved without it is at most this (twice
                                         ///< loop_rejection_chi2: the map's own uncertainty
                                         ///< between the ends counted as one more loop)
  bool final_least_squares = true;       ///< last solve without loss on the accepted loops
  double odometry_xy_information = 2500.0;    ///< x, y information of 1 m of odometry (1/m^2):
                                              ///< sigma 2 cm per metre (wheel odometry, 1-2 %),
                                              ///< divided by the edge's travelled distance
  double odometry_yaw_information = 10000.0;  ///< yaw information of 1 m of odometry (1/rad^2):
                                              ///< sigma 0.6 deg per metre
  double odometry_min_distance_m = 0.1;       ///< shorter odometry edges weigh as this distance
  double loop_xy_information = 44.7;          ///< loop information when none is given (follow-on)
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
    v("odometry_xy_information", odometry_xy_information);
    v("odometry_yaw_information", odometry_yaw_information);
    v("odometry_min_distance_m", odometry_min_distance_m);
    v("loop_xy_information", loop_xy_information);
    v("loop_yaw_information", loop_yaw_information);
    v("max_iterations", max_iterations);
    v("function_tolerance", function_tolerance);
    v("num_threads", num_threads);
  }
};

/// A point target of the simulated environment (e.g. a metal pole), in the world (map) frame.
struct PointTargetConfig {
  double x_m = 0.0;     ///< world position
  double y_m = 0.0;     ///< world position
  double rcs_m2 = 0.5;  ///< radar cross-section (a metal pole: about 0.1 .. 1 m^2)

  template <class V>
  void Visit(V& v) {
    v("x_m", x_m);
    v("y_m", y_m);
    v("rcs_m2", rcs_m2);
  }
};

/// Simulated robot motion along a route (differential drive, trapezoidal speed profiles).
struct SimRouteConfig {
  double speed_mps = 0.2;          ///< cruise speed
  double accel_mps2 = 0.3;         ///< linear acceleration and braking
  double turn_rate_radps = 0.8;    ///< top rate of turns on the spot
  double turn_accel_radps2 = 1.5;  ///< angular acceleration of turns on the spot
  double corner_radius_m = 0.3;    ///< corners up to 120 deg are rounded with this radius;
                                   ///< sharper ones (reversals) stop and turn on the spot
  double pause_s = 1.0;            ///< standstill before the start and after the end
  double start_x_m = 0.0;          ///< built-in routes start here (world frame) ...
  double start_y_m = 0.0;          ///< ...
  double start_yaw_deg = 0.0;      ///< ... heading this way
  double depart_distance_m = 7.5;  ///< depart-return: distance driven out before turning back
  double loop_length_m = 7.0;      ///< loop: rectangle this long along the start heading ...
  double loop_width_m = 0.6;       ///< ... and this wide, turning left
  double clearance_m = 0.15;       ///< a route passing closer to an occupied cell is an error

  template <class V>
  void Visit(V& v) {
    v("speed_mps", speed_mps);
    v("accel_mps2", accel_mps2);
    v("turn_rate_radps", turn_rate_radps);
    v("turn_accel_radps2", turn_accel_radps2);
    v("corner_radius_m", corner_radius_m);
    v("pause_s", pause_s);
    v("start_x_m", start_x_m);
    v("start_y_m", start_y_m);
    v("start_yaw_deg", start_yaw_deg);
    v("depart_distance_m", depart_distance_m);
    v("loop_length_m", loop_length_m);
    v("loop_width_m", loop_width_m);
    v("clearance_m", clearance_m);
  }
};

/// Simulated radar echoes from the occupancy grid and point targets.
struct SimRadarConfig {
  double rate_hz = 100.0;                 ///< scan rate of every radar
  double cell_rcs_m2 = 0.01;              ///< mean radar cross-section of one occupied cell;
                                          ///< each cell draws its own (exponential: speckle)
  int scatterers_per_cell = 4;            ///< random scatterers per occupied cell
  double penetration_depth_m = 0.05;      ///< occupied cells lit behind a ray's first hit
  double max_angle_deg = 80.0;            ///< nothing farther off boresight is seen
  double beam_3db_half_angle_deg = 30.0;  ///< two-way -3 dB angle of the Gaussian beam pattern
  double coupling_amplitude = 0.3;        ///< direct antenna coupling pulse at range 0
  double noise_std = 0.005;               ///< white thermal noise per sample
  std::vector<PointTargetConfig> point_targets;  ///< e.g. metal poles, in the world frame

  template <class V>
  void Visit(V& v) {
    v("rate_hz", rate_hz);
    v("cell_rcs_m2", cell_rcs_m2);
    v("scatterers_per_cell", scatterers_per_cell);
    v("penetration_depth_m", penetration_depth_m);
    v("max_angle_deg", max_angle_deg);
    v("beam_3db_half_angle_deg", beam_3db_half_angle_deg);
    v("coupling_amplitude", coupling_amplitude);
    v("noise_std", noise_std);
    v("point_targets", point_targets);
  }
};

/// Simulated wheel odometry: encoder ticks with systematic and random errors, integrated
/// like the base does (Kobuki figures by default).
struct SimOdometryConfig {
  std::string topic = "/odom";  ///< nav_msgs/Odometry topic of wheel odometry
  std::string ground_truth_topic = "/ground_truth/odom";  ///< topic of the true poses

  double rate_hz = 50.0;                  ///< wheel odometry rate
  double ground_truth_rate_hz = 200.0;    ///< ground-truth pose rate
  double wheel_radius_m = 0.035;          ///< wheel radius the base assumes
  double wheelbase_m = 0.230;             ///< wheel separation the base assumes
  double ticks_per_revolution = 2578.33;  ///< encoder ticks per wheel turn
  double wheel_scale_error = 0.005;       ///< encoders over-report wheel travel by this
                                          ///< fraction (true wheels smaller than assumed; a
                                          ///< calibrated base). No loop on a there-and-back
                                          ///< route can observe it: it bounds any ATE from below
  double wheel_scale_asymmetry = 0.0007;  ///< right minus left scale error: heading drift
                                          ///< of about 1.7 deg per 10 m straight
  double wheelbase_error = 0.02;          ///< true wheelbase is this fraction shorter than
                                          ///< assumed: turns are under-reported
  double wheel_slip_std = 0.01;           ///< random error of each wheel's travel per step,
                                          ///< as a fraction of that travel

  template <class V>
  void Visit(V& v) {
    v("topic", topic);
    v("ground_truth_topic", ground_truth_topic);
    v("rate_hz", rate_hz);
    v("ground_truth_rate_hz", ground_truth_rate_hz);
    v("wheel_radius_m", wheel_radius_m);
    v("wheelbase_m", wheelbase_m);
    v("ticks_per_revolution", ticks_per_revolution);
    v("wheel_scale_error", wheel_scale_error);
    v("wheel_scale_asymmetry", wheel_scale_asymmetry);
    v("wheelbase_error", wheelbase_error);
    v("wheel_slip_std", wheel_slip_std);
  }
};

/// Simulated 2-D LiDAR (sensor_msgs/LaserScan), ray cast in the occupancy grid.
struct SimLaserConfig {
  bool enabled = false;         ///< also write simulated laser scans (`simulate --laser`)
  std::string topic = "/scan";  ///< sensor_msgs/LaserScan topic
  double rate_hz = 10.0;        ///< scan rate
  int num_beams = 360;          ///< beams over a full turn
  double min_range_m = 0.15;    ///< closer returns are reported as invalid
  double max_range_m = 12.0;    ///< farther returns are reported as +inf
  double noise_std_m = 0.01;    ///< Gaussian range noise

  template <class V>
  void Visit(V& v) {
    v("enabled", enabled);
    v("topic", topic);
    v("rate_hz", rate_hz);
    v("num_beams", num_beams);
    v("min_range_m", min_range_m);
    v("max_range_m", max_range_m);
    v("noise_std_m", noise_std_m);
  }
};

/// The environment and robot simulator (`uwbsar simulate`).
struct SimulatorConfig {
  SimRouteConfig route;
  SimRadarConfig radar;
  SimOdometryConfig odometry;
  SimLaserConfig laser;
  double start_time_s = 1700000000.0;  ///< stamp of the first message (s since the Unix epoch)

  template <class V>
  void Visit(V& v) {
    v("route", route);
    v("radar", radar);
    v("odometry", odometry);
    v("laser", laser);
    v("start_time_s", start_time_s);
  }
};
/// Feature detectors on the 8-bit enhanced tile (paper Table II, REFERENCE.md section 3),
/// tuned to about 200 keypoints per tile.
struct DetectorConfig {
  double feature_resolution_m = 0.01;      ///< pixel size features are detected at (tiles are
                                           ///< averaged down to it; 0 = the tile's own, the
                                           ///< paper's 5 mm). Pixel thresholds of detection,
                                           ///< matching and validation are the paper's at the
                                           ///< tile resolution and scale with it
  int max_keypoints = 200;                 ///< keep the strongest this many per tile and detector
  int mask_erode_px = 8;                   ///< detect only this far inside the imaged area
                                           ///< (the sector edges are not scene features)
  double sift_contrast_threshold = 0.015;  ///< SIFT contrastThreshold (paper)
  double surf_hessian_threshold = 200.0;   ///< SURF hessianThreshold (paper)
  int surf_octaves = 4;                    ///< SURF nOctaves (paper)
  int surf_octave_layers = 4;              ///< SURF nOctaveLayers (paper)
  bool surf_upright = false;        ///< U-SURF: no orientation (faster, not rotation invariant)
  int brisk_threshold = 15;         ///< BRISK thresh (paper)
  double akaze_threshold = 0.0005;  ///< AKAZE threshold, KAZE descriptor (paper)
  int orb_fast_threshold = 15;      ///< ORB fastThreshold (paper)
  int orb_wta_k = 4;                ///< ORB WTA_K (paper; 3 and 4 match with Hamming2)

  template <class V>
  void Visit(V& v) {
    v("feature_resolution_m", feature_resolution_m);
    v("max_keypoints", max_keypoints);
    v("mask_erode_px", mask_erode_px);
    v("sift_contrast_threshold", sift_contrast_threshold);
    v("surf_hessian_threshold", surf_hessian_threshold);
    v("surf_octaves", surf_octaves);
    v("surf_octave_layers", surf_octave_layers);
    v("surf_upright", surf_upright);
    v("brisk_threshold", brisk_threshold);
    v("akaze_threshold", akaze_threshold);
    v("orb_fast_threshold", orb_fast_threshold);
    v("orb_wta_k", orb_wta_k);
  }
};

/// Descriptor matching and transform estimation (paper Fig. "matching pipeline").
struct FeatureMatchConfig {
  double ratio = 0.8;                    ///< Lowe ratio test on the two nearest neighbours
  double ransac_reprojection_px = 15.0;  ///< estimateAffinePartial2D RANSAC threshold (paper)
  int ransac_max_iterations = 2000;      ///< RANSAC iterations (OpenCV default)
  double ransac_confidence = 0.99;       ///< RANSAC confidence (OpenCV default)

  template <class V>
  void Visit(V& v) {
    v("ratio", ratio);
    v("ransac_reprojection_px", ransac_reprojection_px);
    v("ransac_max_iterations", ransac_max_iterations);
    v("ransac_confidence", ransac_confidence);
  }
};

/// The paper's AKAZE+ORB loop validation ("Identifying Loop Closures while Exploring")
/// and the uncertainty given to accepted loops.
struct LoopValidationConfig {
  int min_good_matches = 10;           ///< both detectors need more good matches than this (paper)
  double min_scale = 0.85;             ///< both scales must lie in [min_scale, max_scale] (paper)
  double max_scale = 1.15;             ///< ...
  double max_tx_difference_px = 10.0;  ///< |tx_akaze - tx_orb| limit (paper)
  double max_ty_difference_px = 10.0;  ///< |ty_akaze - ty_orb| limit (paper)
  double max_rotation_difference_deg = 10.0;  ///< |rot_akaze - rot_orb| limit (paper)
  double min_inlier_spread_px = 5.0;          ///< the inliers' smaller principal standard deviation
                                      ///< must exceed this (collinear matches are degenerate)
  double min_residual_px = 1.0;    ///< floor of the per-feature position noise used for the
                                   ///< loop's information matrix
  double min_xy_sigma_m = 0.02;    ///< floor of a loop's translation standard deviation:
                                   ///< tiles are imaged with odometry, whose 1-2 % drift
                                   ///< within a tile distorts it by about this much
  double min_yaw_sigma_deg = 0.5;  ///< floor of a loop's rotation standard deviation

  template <class V>
  void Visit(V& v) {
    v("min_good_matches", min_good_matches);
    v("min_scale", min_scale);
    v("max_scale", max_scale);
    v("max_tx_difference_px", max_tx_difference_px);
    v("max_ty_difference_px", max_ty_difference_px);
    v("max_rotation_difference_deg", max_rotation_difference_deg);
    v("min_inlier_spread_px", min_inlier_spread_px);
    v("min_residual_px", min_residual_px);
    v("min_xy_sigma_m", min_xy_sigma_m);
    v("min_yaw_sigma_deg", min_yaw_sigma_deg);
  }
};

/// Which past keyframes a new keyframe is matched against.
struct CandidateSearchConfig {
  bool use_pose_prior = true;          ///< false: every past keyframe is a candidate
                                       ///< (re-localisation after large drift)
  double base_radius_m = 1.0;          ///< search radius around the pose estimate after a loop
  double radius_growth_per_m = 0.1;    ///< radius grows by this per metre of odometry travelled
                                       ///< since the last accepted loop (drift)
  double max_radius_m = 10.0;          ///< radius cap (follow-on: 10 m)
  int max_candidates = 15;             ///< nearest candidates kept (follow-on: 15; 0 = all)
  double exclude_recent_path_m = 3.0;  ///< keyframes that began less than this much path
                                       ///< before the new one are skipped (they share scans)
  double grid_cell_m = 2.0;            ///< cell size of the spatial hash of keyframe positions

  template <class V>
  void Visit(V& v) {
    v("use_pose_prior", use_pose_prior);
    v("base_radius_m", base_radius_m);
    v("radius_growth_per_m", radius_growth_per_m);
    v("max_radius_m", max_radius_m);
    v("max_candidates", max_candidates);
    v("exclude_recent_path_m", exclude_recent_path_m);
    v("grid_cell_m", grid_cell_m);
  }
};

/// Place recognition: loop-closure constraints between keyframe tiles.
struct PlaceRecognitionConfig {
  DetectorConfig detectors;
  FeatureMatchConfig matching;
  LoopValidationConfig validation;
  CandidateSearchConfig candidates;

  template <class V>
  void Visit(V& v) {
    v("detectors", detectors);
    v("matching", matching);
    v("validation", validation);
    v("candidates", candidates);
  }
};

/// Map comparison against a LiDAR occupancy grid (`uwbsar compare`) and PCD export
/// (`uwbsar export-pcd`). Evaluation rule: see backend/compare/map_metrics.h.
struct CompareConfig {
  std::string align = "icp";                  ///< icp (from the map origins or --init) or origin
  std::string icp_method = "point_to_plane";  ///< point_to_plane (2-D normals) or point_to_point
  std::vector<double> icp_max_correspondence_m = {
      1.0, 0.5, 0.25, 0.1};                  ///< coarse-to-fine
                                             ///< ICP stages: pairs farther apart are ignored
  int icp_max_iterations = 50;               ///< ICP iterations per stage
  double icp_transformation_epsilon = 1e-9;  ///< a stage stops when the transform changes less
                                             ///< (PCL: squared translation + rotation change)
  int icp_normal_neighbours = 6;             ///< point_to_plane: cells used for each normal
  double icp_min_inlier_fraction = 0.3;      ///< fewer SAR cells within the last stage's
                                             ///< distance: ICP rejected, initial transform kept
  bool grey_205_unknown = true;              ///< trinary maps: grey 205 is unknown even where
                                             ///< the YAML's free_thresh (Nav2: 0.25) says free
  int tolerance_cells = 1;                   ///< precision / recall / F1 match distance
                                             ///< (cells, 8-neighbourhood)
  int overlay_pixels_per_cell = 4;           ///< overlay.png scale
  double pcd_peak_fraction = 0.2;            ///< export-pcd of a float SAR map: peaks weaker
                                             ///< than this fraction of the strongest are dropped
  double pcd_peak_radius_m = 0.05;           ///< export-pcd: a peak is the maximum within this

  template <class V>
  void Visit(V& v) {
    v("align", align);
    v("icp_method", icp_method);
    v("icp_max_correspondence_m", icp_max_correspondence_m);
    v("icp_max_iterations", icp_max_iterations);
    v("icp_transformation_epsilon", icp_transformation_epsilon);
    v("icp_normal_neighbours", icp_normal_neighbours);
    v("icp_min_inlier_fraction", icp_min_inlier_fraction);
    v("grey_205_unknown", grey_205_unknown);
    v("tolerance_cells", tolerance_cells);
    v("overlay_pixels_per_cell", overlay_pixels_per_cell);
    v("pcd_peak_fraction", pcd_peak_fraction);
    v("pcd_peak_radius_m", pcd_peak_radius_m);
  }
};

/// The SLAM pipeline as `uwbsar map` and live mode run it.
struct SlamConfig {
  std::string odometry_topic = "/odom";  ///< nav_msgs/Odometry topic of wheel odometry
  std::string ground_truth_topic = "/ground_truth/odom";  ///< optional, for evaluation
  double map_resolution_m = 0.01;  ///< pixel size of the global map (map.png, map_float.tif)
  bool keep_tile_images = false;   ///< keep every full-resolution tile in memory after its
                                   ///< features are computed (debugging; costs ~5 MB per metre)
  bool optimize_after_each_loop = true;  ///< re-solve the graph after every accepted loop
                                         ///< (false: once at the end, like the follow-on code)
  double occupancy_resolution_m = 0.05;  ///< cell size of map.pgm (map_server format)
  double occupied_fraction = 0.3;        ///< a cell is occupied when its strongest map pixel
                                         ///< reaches this fraction of the reference level
  double occupancy_reference_percentile = 99.0;  ///< reference level: this percentile of
                                                 ///< the observed map pixels

  template <class V>
  void Visit(V& v) {
    v("odometry_topic", odometry_topic);
    v("ground_truth_topic", ground_truth_topic);
    v("map_resolution_m", map_resolution_m);
    v("keep_tile_images", keep_tile_images);
    v("optimize_after_each_loop", optimize_after_each_loop);
    v("occupancy_resolution_m", occupancy_resolution_m);
    v("occupied_fraction", occupied_fraction);
    v("occupancy_reference_percentile", occupancy_reference_percentile);
  }
};

/// Live mode on the robot (`uwbsar run`): serial devices, GPIO wiring, threads and
/// recording. Device paths and GPIO lines are the robot's; config/robot.yaml is the
/// paper's robot. The LT102 command table is not public (REFERENCE.md section 4), so
/// its command codes are configuration: each command is hex bytes, the first byte the
/// command code and the rest its payload, sent framed (0xFF code payload 0x00).
struct LiveConfig {
  std::vector<std::string> radar_devices = {
      "/dev/ttyACM0", "/dev/ttyACM1"};  ///< serial
                                        ///< device of radars[i] (one per radar)
  int radar_baud = 115200;              ///< LT102 baud rate (SDK default)
  int lt102_raw_data_code = 82;         ///< command byte of the LT102 raw-data message
  std::vector<std::string> lt102_start_commands = {"53 01"};  ///< sent after opening the port
  std::vector<std::string> lt102_stop_commands = {"53 00"};   ///< sent before closing it
  int lt102_channel = 0;                         ///< channel of a multi-channel scan that is used
  std::string kobuki_device = "/dev/kobuki";     ///< Kobuki base serial device
  int kobuki_baud = 115200;                      ///< Kobuki baud rate
  double kobuki_wheel_radius_m = 0.035;          ///< Kobuki wheel radius
  double kobuki_wheelbase_m = 0.230;             ///< Kobuki wheel separation
  double kobuki_ticks_per_revolution = 2578.33;  ///< Kobuki encoder ticks per wheel turn
  double max_wheel_speed_mps = 1.0;    ///< a wheel faster than this between two packets is
                                       ///< an odometry jump: the step is not integrated
  double odometry_stall_s = 0.5;       ///< no odometry for this long: reported as a stall
  std::string gpio_chip = "";          ///< libgpiod chip (e.g. gpiochip0); "" = no GPIO
  std::vector<int> radar_power_lines;  ///< power-enable line of radars[i]; [] = not wired
  std::vector<int> radar_reset_lines;  ///< reset line (active low) of radars[i]; [] = not wired
  int status_led_line = -1;            ///< status LED line; -1 = not wired
  double reset_pulse_s = 0.1;          ///< reset held low this long
  double power_settle_s = 0.5;         ///< wait after power-on and after reset
  double power_off_s = 1.0;            ///< power held off this long in a power cycle
  int power_cycle_after_failures = 3;  ///< reconnect failures before a radar is power cycled
  double read_timeout_s = 1.0;         ///< a link silent this long is reconnected
  double reconnect_initial_s = 0.2;    ///< first reconnect delay, doubled per failure
  double reconnect_max_s = 5.0;        ///< reconnect delay cap
  int processing_queue_size = 4000;    ///< messages waiting for SLAM; beyond, the oldest
                                       ///< are dropped from processing (never from recording)
  double snapshot_period_s = 10.0;     ///< map outputs are rewritten this often (0 = only at end)
  std::string recording_storage = "sqlite3";  ///< recording bag storage: sqlite3 (survives a
                                              ///< crash up to the last flush) or mcap
  double recording_flush_period_s = 0.5;      ///< the recording is made durable this often
  double clock_step_threshold_s = 0.1;        ///< host clock moving this much against the
                                              ///< monotonic clock is reported as a clock step

  template <class V>
  void Visit(V& v) {
    v("radar_devices", radar_devices);
    v("radar_baud", radar_baud);
    v("lt102_raw_data_code", lt102_raw_data_code);
    v("lt102_start_commands", lt102_start_commands);
    v("lt102_stop_commands", lt102_stop_commands);
    v("lt102_channel", lt102_channel);
    v("kobuki_device", kobuki_device);
    v("kobuki_baud", kobuki_baud);
    v("kobuki_wheel_radius_m", kobuki_wheel_radius_m);
    v("kobuki_wheelbase_m", kobuki_wheelbase_m);
    v("kobuki_ticks_per_revolution", kobuki_ticks_per_revolution);
    v("max_wheel_speed_mps", max_wheel_speed_mps);
    v("odometry_stall_s", odometry_stall_s);
    v("gpio_chip", gpio_chip);
    v("radar_power_lines", radar_power_lines);
    v("radar_reset_lines", radar_reset_lines);
    v("status_led_line", status_led_line);
    v("reset_pulse_s", reset_pulse_s);
    v("power_settle_s", power_settle_s);
    v("power_off_s", power_off_s);
    v("power_cycle_after_failures", power_cycle_after_failures);
    v("read_timeout_s", read_timeout_s);
    v("reconnect_initial_s", reconnect_initial_s);
    v("reconnect_max_s", reconnect_max_s);
    v("processing_queue_size", processing_queue_size);
    v("snapshot_period_s", snapshot_period_s);
    v("recording_storage", recording_storage);
    v("recording_flush_period_s", recording_flush_period_s);
    v("clock_step_threshold_s", clock_step_threshold_s);
  }
};

/// The whole configuration; config/default.yaml mirrors it field by field.
struct Config {
  PulseConfig pulse;
  std::vector<RadarConfig> radars = DefaultRadars();
  ImagingConfig imaging;
  GatingConfig gating;
  KeyframeConfig keyframe;
  EnhanceConfig enhance;
  BackendConfig backend;
  SimulatorConfig simulator;
  PlaceRecognitionConfig place_recognition;
  CompareConfig compare;

  SlamConfig slam;
  LiveConfig live;

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
    v("simulator", simulator);
    v("place_recognition", place_recognition);
    v("compare", compare);
    v("live", live);
  }
};

}  // namespace uwbsar
