// Semantic checks of the core sections (ValidateCoreConfig in slam/config_io.h): one
// Validate() per section, declared beside its Visit() in slam/config.h, and the rules that
// join sections. Each failure names the dotted key. The sections owned by higher folders
// are checked by the Validate() beside their own Visit().
#include <array>
#include <cmath>
#include <set>
#include <string>

#include "slam/config_io.h"
#include "slam/config_require.h"

namespace uwbsar {

using config_validation::Require;

void Validate(const PulseConfig& p, const std::string& src) {
  Require(p.center_frequency_hz > 0, src, "pulse.center_frequency_hz", "must be > 0");
  Require(p.bandwidth_hz > 0, src, "pulse.bandwidth_hz", "must be > 0");
  Require(p.sampling_frequency_hz > 2 * p.center_frequency_hz, src, "pulse.sampling_frequency_hz",
          "must exceed twice the centre frequency");
}

void Validate(const std::vector<RadarConfig>& radars, const std::string& src) {
  Require(!radars.empty(), src, "radars", "must list at least one radar");
  for (std::size_t i = 0; i < radars.size(); ++i) {
    const RadarConfig& r = radars[i];
    const std::string k = "radars[" + std::to_string(i) + "].";
    Require(r.fov_half_angle_deg > 0 && r.fov_half_angle_deg <= 90, src, k + "fov_half_angle_deg",
            "must be in (0, 90]");
    Require(r.min_range_m >= 0, src, k + "min_range_m", "must be >= 0");
    Require(r.max_range_m > r.min_range_m, src, k + "max_range_m", "must exceed min_range_m");
    Require(r.num_samples > 1, src, k + "num_samples", "must be > 1");
    Require(r.zero_leading_samples >= 0 && r.zero_leading_samples < r.num_samples, src,
            k + "zero_leading_samples", "must be in [0, num_samples)");
  }
}

void Validate(const ImagingConfig& m, const std::string& src) {
  Require(m.pixel_size_m > 0, src, "imaging.pixel_size_m", "must be > 0");
  Require(m.coherent_oversampling >= 1 && m.coherent_oversampling <= 64, src,
          "imaging.coherent_oversampling", "must be in [1, 64]");
  Require(m.num_threads >= 0, src, "imaging.num_threads", "must be >= 0");
}

void Validate(const GatingConfig& g, const std::string& src) {
  Require(g.min_travel_m >= 0, src, "gating.min_travel_m", "must be >= 0");
  Require(g.max_odom_jump_m > 0, src, "gating.max_odom_jump_m", "must be > 0");
  Require(g.max_odom_gap_s > 0, src, "gating.max_odom_gap_s", "must be > 0");
  Require(g.max_scan_latency_s > 0, src, "gating.max_scan_latency_s", "must be > 0");
  Require(g.max_odom_speed_mps > 0, src, "gating.max_odom_speed_mps", "must be > 0");
  Require(g.max_odom_turn_rate_radps > 0, src, "gating.max_odom_turn_rate_radps", "must be > 0");
}

void Validate(const KeyframeConfig& k, const std::string& src) {
  Require(k.tile_length_m > 0, src, "keyframe.tile_length_m", "must be > 0");
  Require(k.tile_spacing_m > 0 && k.tile_spacing_m <= k.tile_length_m, src,
          "keyframe.tile_spacing_m", "must be in (0, tile_length_m]");
  const double ratio = k.tile_length_m / k.tile_spacing_m;
  Require(std::abs(ratio - std::round(ratio)) < 1e-6, src, "keyframe.tile_length_m",
          "must be a whole multiple of keyframe.tile_spacing_m");
  Require(k.margin_m >= 0, src, "keyframe.margin_m", "must be >= 0");
}

void Validate(const EnhanceConfig& e, const std::string& src) {
  Require(e.blur_sigma_px >= 0, src, "enhance.blur_sigma_px", "must be >= 0");
  Require(e.display_range_db > 0, src, "enhance.display_range_db", "must be > 0");
  static const std::set<std::string> kColormaps = {"gray",    "inferno", "jet",
                                                   "viridis", "magma",   "hot"};
  Require(kColormaps.count(e.colormap) > 0, src, "enhance.colormap",
          "must be one of gray, inferno, jet, viridis, magma, hot");
}

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
  Require(b.calibration_scale_sigma > 0, src, "backend.calibration_scale_sigma", "must be > 0");
  Require(b.calibration_heading_drift_sigma_rad_per_m > 0, src,
          "backend.calibration_heading_drift_sigma_rad_per_m", "must be > 0");
  Require(b.calibration_rotation_sigma > 0, src, "backend.calibration_rotation_sigma",
          "must be > 0");
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

namespace {

// The subsections of place_recognition, in the file's order; `k` is "place_recognition.".
void ValidateDetectors(const DetectorConfig& d, const std::string& src, const std::string& k) {
  Require(d.max_keypoints >= 1 && d.max_keypoints <= 100000, src, k + "detectors.max_keypoints",
          "must be in [1, 100000]");
  Require(d.mask_erode_px >= 0 && d.mask_erode_px <= 1000, src, k + "detectors.mask_erode_px",
          "must be in [0, 1000]");
  Require(d.sift_contrast_threshold > 0, src, k + "detectors.sift_contrast_threshold",
          "must be > 0");
  Require(d.surf_hessian_threshold >= 0, src, k + "detectors.surf_hessian_threshold",
          "must be >= 0");
  Require(d.surf_octaves >= 1 && d.surf_octaves <= 8, src, k + "detectors.surf_octaves",
          "must be in [1, 8]");
  Require(d.surf_octave_layers >= 1 && d.surf_octave_layers <= 8, src,
          k + "detectors.surf_octave_layers", "must be in [1, 8]");
  Require(d.brisk_threshold >= 1 && d.brisk_threshold <= 255, src, k + "detectors.brisk_threshold",
          "must be in [1, 255]");
  Require(d.akaze_threshold > 0, src, k + "detectors.akaze_threshold", "must be > 0");
  Require(d.orb_fast_threshold >= 1 && d.orb_fast_threshold <= 255, src,
          k + "detectors.orb_fast_threshold", "must be in [1, 255]");
  Require(d.orb_wta_k >= 2 && d.orb_wta_k <= 4, src, k + "detectors.orb_wta_k",
          "must be 2, 3 or 4");
}

void ValidateMatching(const FeatureMatchConfig& m, const std::string& src, const std::string& k) {
  Require(m.ratio > 0 && m.ratio <= 1, src, k + "matching.ratio", "must be in (0, 1]");
  Require(m.ransac_reprojection_px > 0, src, k + "matching.ransac_reprojection_px", "must be > 0");
  Require(m.ransac_max_iterations >= 1, src, k + "matching.ransac_max_iterations", "must be >= 1");
  Require(m.ransac_confidence > 0 && m.ransac_confidence < 1, src, k + "matching.ransac_confidence",
          "must be in (0, 1)");
}

void ValidateLoopValidation(const LoopValidationConfig& v, const std::string& src,
                            const std::string& k) {
  Require(v.min_good_matches >= 2, src, k + "validation.min_good_matches", "must be >= 2");
  Require(v.min_scale > 0 && v.min_scale <= 1, src, k + "validation.min_scale",
          "must be in (0, 1]");
  Require(v.max_scale >= 1, src, k + "validation.max_scale", "must be >= 1");
  Require(v.max_tx_difference_px >= 0, src, k + "validation.max_tx_difference_px", "must be >= 0");
  Require(v.max_ty_difference_px >= 0, src, k + "validation.max_ty_difference_px", "must be >= 0");
  Require(v.max_rotation_difference_deg >= 0 && v.max_rotation_difference_deg <= 180, src,
          k + "validation.max_rotation_difference_deg", "must be in [0, 180]");
  Require(v.min_inlier_spread_px >= 0, src, k + "validation.min_inlier_spread_px", "must be >= 0");
  Require(v.min_residual_px > 0, src, k + "validation.min_residual_px", "must be > 0");
  Require(v.min_xy_sigma_m > 0, src, k + "validation.min_xy_sigma_m", "must be > 0");
  Require(v.min_yaw_sigma_deg > 0, src, k + "validation.min_yaw_sigma_deg", "must be > 0");
}

void ValidateCandidates(const CandidateSearchConfig& c, const std::string& src,
                        const std::string& k) {
  Require(c.base_radius_m > 0, src, k + "candidates.base_radius_m", "must be > 0");
  Require(c.radius_growth_per_m >= 0, src, k + "candidates.radius_growth_per_m", "must be >= 0");
  Require(c.max_radius_m >= c.base_radius_m, src, k + "candidates.max_radius_m",
          "must be >= base_radius_m");
  Require(c.max_candidates >= 0, src, k + "candidates.max_candidates", "must be >= 0");
  Require(c.exclude_recent_path_m >= 0, src, k + "candidates.exclude_recent_path_m",
          "must be >= 0");
  Require(c.grid_cell_m > 0, src, k + "candidates.grid_cell_m", "must be > 0");
  Require(c.global_search_after_m >= 0, src, k + "candidates.global_search_after_m",
          "must be >= 0");
  Require(c.global_search_every_m >= 0, src, k + "candidates.global_search_every_m",
          "must be >= 0 (0 = never)");
}

void ValidateGuided(const GuidedMatchConfig& g, const std::string& src, const std::string& k) {
  Require(g.neighbours >= 0, src, k + "guided.neighbours", "must be >= 0 (0 = off)");
  Require(g.min_good_matches >= 2, src, k + "guided.min_good_matches", "must be >= 2");
  Require(g.max_offset_m > 0, src, k + "guided.max_offset_m", "must be > 0");
  Require(g.max_yaw_deg > 0 && g.max_yaw_deg <= 180, src, k + "guided.max_yaw_deg",
          "must be in (0, 180]");
  Require(g.max_centre_distance_m > 0, src, k + "guided.max_centre_distance_m", "must be > 0");
}

void ValidatePerRadar(const RadarMatchConfig& r, const std::string& src, const std::string& k) {
  Require(r.max_keypoints >= 2 && r.max_keypoints <= 100000, src, k + "per_radar.max_keypoints",
          "must be in [2, 100000]");
  Require(r.max_look_difference_deg >= 0 && r.max_look_difference_deg <= 180, src,
          k + "per_radar.max_look_difference_deg", "must be in [0, 180]");
}

void ValidateWallProfiles(const WallProfileConfig& w, const std::string& src,
                          const std::string& k) {
  Require(w.min_gap >= 1, src, k + "wall_profiles.min_gap", "must be >= 1");
  Require(w.max_gap >= w.min_gap && w.max_gap <= 100, src, k + "wall_profiles.max_gap",
          "must be in [wall_profiles.min_gap, 100]");
  Require(w.max_heading_change_deg > 0 && w.max_heading_change_deg <= 45, src,
          k + "wall_profiles.max_heading_change_deg", "must be in (0, 45]");
  Require(w.bin_m > 0 && w.bin_m <= 0.1, src, k + "wall_profiles.bin_m", "must be in (0, 0.1]");
  Require(w.half_width_m >= 10 * w.bin_m && w.half_width_m / w.bin_m <= 1e5, src,
          k + "wall_profiles.half_width_m", "must be in [10, 1e5] x wall_profiles.bin_m");
  Require(w.search_m >= w.bin_m && w.search_m < w.half_width_m, src, k + "wall_profiles.search_m",
          "must be in [bin_m, half_width_m)");
  Require(w.min_wall_contrast >= 1, src, k + "wall_profiles.min_wall_contrast", "must be >= 1");
  Require(w.min_correlation > 0 && w.min_correlation <= 1, src, k + "wall_profiles.min_correlation",
          "must be in (0, 1]");
  Require(w.lateral_std_m > 0, src, k + "wall_profiles.lateral_std_m", "must be > 0");
}

}  // namespace

void Validate(const PlaceRecognitionConfig& p, const std::string& src) {
  const std::string k = "place_recognition.";
  ValidateDetectors(p.detectors, src, k);
  ValidateMatching(p.matching, src, k);
  ValidateLoopValidation(p.validation, src, k);
  ValidateCandidates(p.candidates, src, k);
  ValidateGuided(p.guided, src, k);
  ValidatePerRadar(p.per_radar, src, k);
  ValidateWallProfiles(p.wall_profiles, src, k);
}

void Validate(const SlamConfig& s, const std::string& src) {
  Require(s.map_resolution_m > 0, src, "slam.map_resolution_m", "must be > 0");
  Require(s.optimize_every_keyframes >= 0, src, "slam.optimize_every_keyframes", "must be >= 0");
  Require(s.keyframe_queue_size >= 1, src, "slam.keyframe_queue_size", "must be >= 1");
  Require(!s.odometry_topic.empty(), src, "slam.odometry_topic", "must not be empty");
  Require(s.occupancy_resolution_m >= s.map_resolution_m, src, "slam.occupancy_resolution_m",
          "must be >= slam.map_resolution_m");
  Require(s.occupied_fraction > 0 && s.occupied_fraction <= 1, src, "slam.occupied_fraction",
          "must be in (0, 1]");
  Require(s.occupancy_reference_percentile > 0 && s.occupancy_reference_percentile <= 100, src,
          "slam.occupancy_reference_percentile", "must be in (0, 100]");
}

namespace {

/// The rules that join sections: topics (radars against slam) and the feature resolution
/// (place_recognition against imaging).
void ValidateAcrossSections(const CoreConfig& c, const std::string& src) {
  Require(c.place_recognition.detectors.feature_resolution_m == 0 ||
              c.place_recognition.detectors.feature_resolution_m >= c.imaging.pixel_size_m,
          src, "place_recognition.detectors.feature_resolution_m",
          "must be 0 or >= imaging.pixel_size_m");
  for (std::size_t i = 0; i < c.radars.size(); ++i) {
    const std::string key = "radars[" + std::to_string(i) + "].topic";
    Require(c.radars[i].topic != c.slam.odometry_topic, src, key,
            "must differ from slam.odometry_topic ('" + c.slam.odometry_topic + "')");
    for (std::size_t j = 0; j < i; ++j) {
      Require(c.radars[i].topic != c.radars[j].topic, src, key,
              "must differ from radars[" + std::to_string(j) + "].topic");
    }
  }
}

}  // namespace

void ValidateCoreConfig(const CoreConfig& c, const std::string& src) {
  Validate(c.place_recognition, src);
  Validate(c.pulse, src);
  Validate(c.radars, src);
  Validate(c.slam, src);
  ValidateAcrossSections(c, src);
  Validate(c.imaging, src);
  Validate(c.gating, src);
  Validate(c.keyframe, src);
  Validate(c.enhance, src);
  Validate(c.backend, src);
  ValidateLimits(c, src);  // last: the sizes it derives assume the plain range checks passed
}

}  // namespace uwbsar
