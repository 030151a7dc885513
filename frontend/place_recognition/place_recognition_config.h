// Configuration of place recognition: detectors, matching, loop validation, candidates.
// Part of the configuration (slam/config/system_config.h includes it); fields are read and
// written by the generic loader in core/config_io.h.
#pragma once

#include <string>
#include <vector>

#include "frontend/place_recognition/detector_kind.h"
#include "frontend/place_recognition/map_registration_config.h"
#include "frontend/place_recognition/radar_match_config.h"
#include "frontend/wall_profile_config.h"

namespace uwbsar {

/// Feature detectors on the 8-bit enhanced tile (paper Table II),
/// tuned to about 200 keypoints per tile.
struct DetectorConfig {
  double feature_resolution_m = 0.01;      ///< pixel size features are detected at (tiles are
                                           ///< averaged down to it; 0 = the tile's own, the
                                           ///< paper's 5 mm). Pixel thresholds of detection,
                                           ///< matching and validation are the paper's at the
                                           ///< tile resolution and scale with it
  double white_percentile = 99.5;          ///< contrast of the 8-bit feature image: this
                                           ///< percentile of the measured pixels maps to 255
                                           ///< (brighter ones saturate; 100 = min-max, the
                                           ///< paper, which leaves real scenes too dark)
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
    v("white_percentile", white_percentile);
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
  double ransac_reprojection_px = 10.0;  ///< estimateAffinePartial2D RANSAC threshold (paper:
                                         ///< 15; 10 = 5 cm keeps detectors consistent on real
                                         ///< walls, along which matches can slide)
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

/// Dense refinement of a pair whose two detectors nearly agree (dense_refinement.h): both
/// feature images are correlated (masked normalised cross-correlation) over a small window of
/// shifts and rotations around the detectors' fused transform; the pair is accepted when both
/// detectors lie within the rule's agreement limits of the correlation peak and the peak is
/// distinct. The rule's own limits are not moved: a pair the rule accepts is never refined.
struct DenseRefinementConfig {
  bool enabled = false;  ///< off by default: on floor50's 5 km it took matching from 5-8 to
                         ///< 62-135 ms/m for 64 more loops of 20 400 (docs/measurements.md)
  double near_agreement_factor = 1.5;  ///< refine when every difference of the pair is within
                                       ///< this many times its limit (tx, ty, rotation)
  double search_m = 0.06;              ///< shifts searched, +- this around the fused transform
  double search_deg = 1.5;             ///< rotations searched, +- this ...
  double step_deg = 0.25;              ///< ... in steps of this
  double min_peak_ratio = 1.1;         ///< the correlation peak over the second peak: the
                                       ///< highest correlation outside the peak's lobe (the
                                       ///< shifts around it above half the peak), or the lobe's
                                       ///< highest on the window's edge when it reaches it
  double min_peak_ncc = 0.3;           ///< the peak's correlation at least this (real
                                       ///< corridor: true pairs 0.40-0.56, wrong ones <= 0.15)
  double highpass_sigma_m = 0.03;      ///< the images' local mean (Gaussian of this sigma) is
                                       ///< taken off before correlating: broad echo bands would
                                       ///< make every nearby shift correlate alike
  double min_overlap_fraction = 0.2;   ///< the overlap of the measured areas at the fused
                                       ///< transform, of the smaller one, at least this

  template <class V>
  void Visit(V& v) {
    v("enabled", enabled);
    v("near_agreement_factor", near_agreement_factor);
    v("search_m", search_m);
    v("search_deg", search_deg);
    v("step_deg", step_deg);
    v("min_peak_ratio", min_peak_ratio);
    v("min_peak_ncc", min_peak_ncc);
    v("highpass_sigma_m", highpass_sigma_m);
    v("min_overlap_fraction", min_overlap_fraction);
  }
};

/// The paper's loop validation ("Identifying Loop Closures while Exploring") on a pair of
/// detectors, AKAZE+ORB by default, and the uncertainty given to accepted loops.
struct LoopValidationConfig {
  /// The two detectors whose transforms must agree (the paper's AKAZE and ORB); only their
  /// features are computed, matched and stored. The first one's rotation anchors the fusion.
  std::vector<DetectorKind> detectors = PaperDetectorPair();
  int min_good_matches = 10;           ///< both detectors need more good matches than this (paper)
  double min_scale = 0.85;             ///< both scales must lie in [min_scale, max_scale] (paper)
  double max_scale = 1.15;             ///< ...
  double max_tx_difference_px = 10.0;  ///< |tx_a - tx_b| limit of the pair (paper)
  double max_ty_difference_px = 10.0;  ///< |ty_a - ty_b| limit of the pair (paper)
  double max_rotation_difference_deg = 10.0;  ///< |rot_a - rot_b| limit of the pair (paper)
  double min_inlier_spread_px = 5.0;          ///< the inliers' smaller principal standard deviation
                                      ///< must exceed this (collinear matches are degenerate)
  double min_residual_px = 1.0;      ///< floor of the per-feature position noise used for the
                                     ///< loop's information matrix
  double min_xy_sigma_m = 0.02;      ///< floor of a loop's translation standard deviation:
                                     ///< tiles are imaged with odometry, whose 1-2 % drift
                                     ///< within a tile distorts it by about this much
  double min_yaw_sigma_deg = 0.5;    ///< floor of a loop's rotation standard deviation
  DenseRefinementConfig refinement;  ///< near agreements refined by dense correlation

  template <class V>
  void Visit(V& v) {
    v("detectors", detectors);
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
    v("refinement", refinement);
  }
};

/// Which past keyframes a new keyframe is matched against.
struct CandidateSearchConfig {
  bool use_pose_prior = true;           ///< false: every past keyframe is a candidate
                                        ///< (re-localisation after large drift)
  double base_radius_m = 1.0;           ///< search radius around the pose estimate after a loop
  double radius_growth_per_m = 0.1;     ///< radius grows by this per metre of odometry travelled
                                        ///< since the last accepted loop (drift)
  double max_radius_m = 10.0;           ///< radius cap (follow-on: 10 m)
  double global_search_after_m = 20.0;  ///< no accepted loop for this much odometry path: drift
                                        ///< may exceed the radius, so ...
  double global_search_every_m = 5.0;   ///< ... one keyframe per this much path is matched
                                        ///< against every past keyframe (0 = never)
  int max_candidates = 15;              ///< nearest candidates kept (follow-on: 15; 0 = all)
  double exclude_recent_path_m = 3.0;   ///< keyframes that began less than this much path
                                        ///< before the new one are skipped (they share scans)
  double grid_cell_m = 2.0;             ///< cell size of the spatial hash of keyframe positions
  /// Not a key: how fast the odometry's heading error may grow (rad/s, one sigma). A gyro base's
  /// bias spread (backend.gyro_bias_sigma_dps with backend.odometry_model gyro, set by the SLAM
  /// system); 0 for a wheel base, whose heading error grows with the path (radius_growth_per_m).
  double heading_rate_sigma_radps = 0.0;

  template <class V>
  void Visit(V& v) {
    v("use_pose_prior", use_pose_prior);
    v("base_radius_m", base_radius_m);
    v("radius_growth_per_m", radius_growth_per_m);
    v("max_radius_m", max_radius_m);
    v("global_search_after_m", global_search_after_m);
    v("global_search_every_m", global_search_every_m);
    v("max_candidates", max_candidates);
    v("exclude_recent_path_m", exclude_recent_path_m);
    v("grid_cell_m", grid_cell_m);
  }
};

/// Guided pass around a validated loop: the keyframes just before and after the
/// loop's new keyframe are matched against the old keyframes the loop predicts them to
/// overlap; the AKAZE+ORB rule runs with a lower good-match threshold, and a pair counts only
/// when its transform agrees with the loop's prediction. The pairs become loops of their
/// own, so a ring closure that would stand alone gets neighbours that support it.
struct GuidedMatchConfig {
  int neighbours = 3;                  ///< keyframes on each side of the loop's new one (0 = off)
  int min_good_matches = 5;            ///< both detectors need more good matches than this
  double max_offset_m = 0.15;          ///< the pair's transform within this of the prediction ...
  double max_yaw_deg = 3.0;            ///< ... and within this rotation
  double max_centre_distance_m = 1.0;  ///< predicted distance between the tiles' centres

  template <class V>
  void Visit(V& v) {
    v("neighbours", neighbours);
    v("min_good_matches", min_good_matches);
    v("max_offset_m", max_offset_m);
    v("max_yaw_deg", max_yaw_deg);
    v("max_centre_distance_m", max_centre_distance_m);
  }
};

/// Place recognition: loop-closure constraints between keyframe tiles.
struct PlaceRecognitionConfig {
  DetectorConfig detectors;
  FeatureMatchConfig matching;
  LoopValidationConfig validation;
  CandidateSearchConfig candidates;
  GuidedMatchConfig guided;
  RadarMatchConfig per_radar;
  WallProfileConfig wall_profiles;
  MapRegistrationConfig registration;  ///< localisation's registration against the map's tiles

  template <class V>
  void Visit(V& v) {
    v("detectors", detectors);
    v("matching", matching);
    v("validation", validation);
    v("candidates", candidates);
    v("guided", guided);
    v("per_radar", per_radar);
    v("wall_profiles", wall_profiles);
    v("registration", registration);
  }
};

/// Semantic checks of place_recognition.* (the feature resolution against imaging is in
/// ValidateSystemConfig); throws ConfigError naming the dotted key.
void Validate(const PlaceRecognitionConfig& config, const std::string& source_name);

}  // namespace uwbsar
