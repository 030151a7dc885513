// Semantic checks of a loaded configuration (ValidateConfig in slam/config_io.h):
// positive sizes, known modes, consistent ranges. Each failure names the dotted key.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <set>
#include <string>

#include "slam/config_io.h"
#include "slam/config_validation_parts.h"

namespace uwbsar {
namespace {

using config_validation::Require;
using config_validation::ValidateDds;
using config_validation::ValidateLimits;
using config_validation::ValidateLive;

void ValidateSimulator(const SimulatorConfig& s, const std::string& src) {
  const std::string k = "simulator.";
  const SimRouteConfig& r = s.route;
  Require(r.speed_mps > 0 && r.speed_mps <= 5, src, k + "route.speed_mps", "must be in (0, 5]");
  Require(r.accel_mps2 > 0, src, k + "route.accel_mps2", "must be > 0");
  Require(r.turn_rate_radps > 0, src, k + "route.turn_rate_radps", "must be > 0");
  Require(r.turn_accel_radps2 > 0, src, k + "route.turn_accel_radps2", "must be > 0");
  Require(r.corner_radius_m >= 0, src, k + "route.corner_radius_m", "must be >= 0");
  Require(r.pause_s >= 0, src, k + "route.pause_s", "must be >= 0");
  Require(r.depart_distance_m > 0, src, k + "route.depart_distance_m", "must be > 0");
  Require(r.loop_length_m > 0, src, k + "route.loop_length_m", "must be > 0");
  Require(r.loop_width_m > 0, src, k + "route.loop_width_m", "must be > 0");
  Require(r.clearance_m >= 0, src, k + "route.clearance_m", "must be >= 0");
  const SimRadarConfig& a = s.radar;
  Require(a.rate_hz > 0 && a.rate_hz <= 10000, src, k + "radar.rate_hz", "must be in (0, 10000]");
  Require(a.cell_rcs_m2 >= 0, src, k + "radar.cell_rcs_m2", "must be >= 0");
  Require(a.scatterers_per_cell >= 1 && a.scatterers_per_cell <= 64, src,
          k + "radar.scatterers_per_cell", "must be in [1, 64]");
  Require(a.penetration_depth_m >= 0, src, k + "radar.penetration_depth_m", "must be >= 0");
  Require(a.max_angle_deg > 0 && a.max_angle_deg <= 180, src, k + "radar.max_angle_deg",
          "must be in (0, 180]");
  Require(a.beam_3db_half_angle_deg > 0, src, k + "radar.beam_3db_half_angle_deg", "must be > 0");
  Require(a.noise_std >= 0, src, k + "radar.noise_std", "must be >= 0");
  for (std::size_t i = 0; i < a.point_targets.size(); ++i) {
    Require(a.point_targets[i].rcs_m2 >= 0, src,
            k + "radar.point_targets[" + std::to_string(i) + "].rcs_m2", "must be >= 0");
  }
  const SimOdometryConfig& o = s.odometry;
  Require(!o.topic.empty(), src, k + "odometry.topic", "must not be empty");
  Require(!o.ground_truth_topic.empty() && o.ground_truth_topic != o.topic, src,
          k + "odometry.ground_truth_topic", "must be set and differ from odometry.topic");
  Require(o.rate_hz > 0 && o.rate_hz <= 10000, src, k + "odometry.rate_hz",
          "must be in (0, 10000]");
  Require(o.ground_truth_rate_hz > 0 && o.ground_truth_rate_hz <= 10000, src,
          k + "odometry.ground_truth_rate_hz", "must be in (0, 10000]");
  Require(o.wheel_radius_m > 0, src, k + "odometry.wheel_radius_m", "must be > 0");
  Require(o.wheelbase_m > 0, src, k + "odometry.wheelbase_m", "must be > 0");
  Require(o.ticks_per_revolution > 0, src, k + "odometry.ticks_per_revolution", "must be > 0");
  Require(std::abs(o.wheel_scale_error) < 0.5, src, k + "odometry.wheel_scale_error",
          "must be in (-0.5, 0.5)");
  Require(std::abs(o.wheel_scale_asymmetry) < 0.5, src, k + "odometry.wheel_scale_asymmetry",
          "must be in (-0.5, 0.5)");
  Require(std::abs(o.wheelbase_error) < 0.5, src, k + "odometry.wheelbase_error",
          "must be in (-0.5, 0.5)");
  Require(o.wheel_slip_std >= 0 && o.wheel_slip_std < 1, src, k + "odometry.wheel_slip_std",
          "must be in [0, 1)");
  const SimLaserConfig& l = s.laser;
  Require(!l.topic.empty(), src, k + "laser.topic", "must not be empty");
  Require(l.rate_hz > 0 && l.rate_hz <= 1000, src, k + "laser.rate_hz", "must be in (0, 1000]");
  Require(l.num_beams >= 1 && l.num_beams <= 100000, src, k + "laser.num_beams",
          "must be in [1, 100000]");
  Require(l.min_range_m >= 0, src, k + "laser.min_range_m", "must be >= 0");
  Require(l.max_range_m > l.min_range_m, src, k + "laser.max_range_m", "must exceed min_range_m");
  Require(l.noise_std_m >= 0, src, k + "laser.noise_std_m", "must be >= 0");
  Require(s.start_time_s >= 0 && s.start_time_s < 9e9, src, k + "start_time_s",
          "must be in [0, 9e9)");
}

void ValidatePlaceRecognition(const PlaceRecognitionConfig& p, const std::string& src) {
  const std::string k = "place_recognition.";
  const DetectorConfig& d = p.detectors;
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
  const FeatureMatchConfig& m = p.matching;
  Require(m.ratio > 0 && m.ratio <= 1, src, k + "matching.ratio", "must be in (0, 1]");
  Require(m.ransac_reprojection_px > 0, src, k + "matching.ransac_reprojection_px", "must be > 0");
  Require(m.ransac_max_iterations >= 1, src, k + "matching.ransac_max_iterations", "must be >= 1");
  Require(m.ransac_confidence > 0 && m.ransac_confidence < 1, src, k + "matching.ransac_confidence",
          "must be in (0, 1)");
  const LoopValidationConfig& v = p.validation;
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
  const CandidateSearchConfig& c = p.candidates;
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
  const GuidedMatchConfig& g = p.guided;
  Require(g.neighbours >= 0, src, k + "guided.neighbours", "must be >= 0 (0 = off)");
  Require(g.min_good_matches >= 2, src, k + "guided.min_good_matches", "must be >= 2");
  Require(g.max_offset_m > 0, src, k + "guided.max_offset_m", "must be > 0");
  Require(g.max_yaw_deg > 0 && g.max_yaw_deg <= 180, src, k + "guided.max_yaw_deg",
          "must be in (0, 180]");
  Require(g.max_centre_distance_m > 0, src, k + "guided.max_centre_distance_m", "must be > 0");
  const RadarMatchConfig& r = p.per_radar;
  Require(r.max_keypoints >= 2 && r.max_keypoints <= 100000, src, k + "per_radar.max_keypoints",
          "must be in [2, 100000]");
  Require(r.max_look_difference_deg >= 0 && r.max_look_difference_deg <= 180, src,
          k + "per_radar.max_look_difference_deg", "must be in [0, 180]");
}

void ValidateCompare(const CompareConfig& c, const std::string& src) {
  const std::string k = "compare.";
  Require(c.icp_method == "point_to_point" || c.icp_method == "point_to_plane", src,
          k + "icp_method", "must be 'point_to_point' or 'point_to_plane'");
  Require(!c.icp_max_correspondence_m.empty(), src, k + "icp_max_correspondence_m",
          "must list at least one distance");
  for (double d : c.icp_max_correspondence_m) {
    Require(d > 0, src, k + "icp_max_correspondence_m", "distances must be > 0");
  }
  Require(c.icp_max_iterations >= 1, src, k + "icp_max_iterations", "must be >= 1");
  Require(c.icp_transformation_epsilon > 0, src, k + "icp_transformation_epsilon", "must be > 0");
  Require(c.icp_normal_neighbours >= 3 && c.icp_normal_neighbours <= 100, src,
          k + "icp_normal_neighbours", "must be in [3, 100]");
  Require(c.icp_min_inlier_fraction >= 0 && c.icp_min_inlier_fraction <= 1, src,
          k + "icp_min_inlier_fraction", "must be in [0, 1]");
  Require(c.tolerance_cells >= 0 && c.tolerance_cells <= 50, src, k + "tolerance_cells",
          "must be in [0, 50]");
  Require(c.overlay_pixels_per_cell >= 1 && c.overlay_pixels_per_cell <= 32, src,
          k + "overlay_pixels_per_cell", "must be in [1, 32]");
  Require(c.pcd_peak_fraction >= 0 && c.pcd_peak_fraction < 1, src, k + "pcd_peak_fraction",
          "must be in [0, 1)");
  Require(c.pcd_peak_radius_m > 0, src, k + "pcd_peak_radius_m", "must be > 0");
}

/// Pulse and radars.
void ValidateSensors(const Config& c, const std::string& src) {
  Require(c.pulse.center_frequency_hz > 0, src, "pulse.center_frequency_hz", "must be > 0");
  Require(c.pulse.bandwidth_hz > 0, src, "pulse.bandwidth_hz", "must be > 0");
  Require(c.pulse.sampling_frequency_hz > 2 * c.pulse.center_frequency_hz, src,
          "pulse.sampling_frequency_hz", "must exceed twice the centre frequency");
  Require(!c.radars.empty(), src, "radars", "must list at least one radar");
  for (std::size_t i = 0; i < c.radars.size(); ++i) {
    const RadarConfig& r = c.radars[i];
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

/// slam.*, with the radar topics and the feature resolution that depend on it.
void ValidateSlam(const Config& c, const std::string& src) {
  Require(c.slam.map_resolution_m > 0, src, "slam.map_resolution_m", "must be > 0");
  Require(c.slam.optimize_every_keyframes >= 0, src, "slam.optimize_every_keyframes",
          "must be >= 0");
  Require(c.slam.keyframe_queue_size >= 1, src, "slam.keyframe_queue_size", "must be >= 1");
  Require(c.place_recognition.detectors.feature_resolution_m == 0 ||
              c.place_recognition.detectors.feature_resolution_m >= c.imaging.pixel_size_m,
          src, "place_recognition.detectors.feature_resolution_m",
          "must be 0 or >= imaging.pixel_size_m");
  Require(!c.slam.odometry_topic.empty(), src, "slam.odometry_topic", "must not be empty");
  for (std::size_t i = 0; i < c.radars.size(); ++i) {
    const std::string key = "radars[" + std::to_string(i) + "].topic";
    Require(c.radars[i].topic != c.slam.odometry_topic, src, key,
            "must differ from slam.odometry_topic ('" + c.slam.odometry_topic + "')");
    for (std::size_t j = 0; j < i; ++j) {
      Require(c.radars[i].topic != c.radars[j].topic, src, key,
              "must differ from radars[" + std::to_string(j) + "].topic");
    }
  }
  Require(c.slam.occupancy_resolution_m >= c.slam.map_resolution_m, src,
          "slam.occupancy_resolution_m", "must be >= slam.map_resolution_m");
  Require(c.slam.occupied_fraction > 0 && c.slam.occupied_fraction <= 1, src,
          "slam.occupied_fraction", "must be in (0, 1]");
  Require(c.slam.occupancy_reference_percentile > 0 && c.slam.occupancy_reference_percentile <= 100,
          src, "slam.occupancy_reference_percentile", "must be in (0, 100]");
}

/// imaging, gating, keyframe and enhance.
void ValidateImaging(const Config& c, const std::string& src) {
  Require(c.imaging.pixel_size_m > 0, src, "imaging.pixel_size_m", "must be > 0");
  Require(c.imaging.coherent_oversampling >= 1 && c.imaging.coherent_oversampling <= 64, src,
          "imaging.coherent_oversampling", "must be in [1, 64]");
  Require(c.imaging.num_threads >= 0, src, "imaging.num_threads", "must be >= 0");
  Require(c.gating.min_travel_m >= 0, src, "gating.min_travel_m", "must be >= 0");
  Require(c.gating.max_odom_jump_m > 0, src, "gating.max_odom_jump_m", "must be > 0");
  Require(c.gating.max_odom_gap_s > 0, src, "gating.max_odom_gap_s", "must be > 0");
  Require(c.gating.max_scan_latency_s > 0, src, "gating.max_scan_latency_s", "must be > 0");
  Require(c.keyframe.tile_length_m > 0, src, "keyframe.tile_length_m", "must be > 0");
  Require(c.keyframe.tile_spacing_m > 0 && c.keyframe.tile_spacing_m <= c.keyframe.tile_length_m,
          src, "keyframe.tile_spacing_m", "must be in (0, tile_length_m]");
  {
    const double ratio = c.keyframe.tile_length_m / c.keyframe.tile_spacing_m;
    Require(std::abs(ratio - std::round(ratio)) < 1e-6, src, "keyframe.tile_length_m",
            "must be a whole multiple of keyframe.tile_spacing_m");
  }
  Require(c.keyframe.margin_m >= 0, src, "keyframe.margin_m", "must be >= 0");
  Require(c.enhance.blur_sigma_px >= 0, src, "enhance.blur_sigma_px", "must be >= 0");
  Require(c.enhance.display_range_db > 0, src, "enhance.display_range_db", "must be > 0");
  static const std::set<std::string> kColormaps = {"gray",    "inferno", "jet",
                                                   "viridis", "magma",   "hot"};
  Require(kColormaps.count(c.enhance.colormap) > 0, src, "enhance.colormap",
          "must be one of gray, inferno, jet, viridis, magma, hot");
}

void ValidateBackend(const BackendConfig& b, const std::string& src) {
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
  Require(b.loop_xy_information > 0, src, "backend.loop_xy_information", "must be > 0");
  Require(b.loop_yaw_information > 0, src, "backend.loop_yaw_information", "must be > 0");
  Require(b.max_iterations >= 1, src, "backend.max_iterations", "must be >= 1");
  Require(b.function_tolerance > 0 && b.function_tolerance < 1, src, "backend.function_tolerance",
          "must be in (0, 1)");
  Require(b.num_threads >= 1, src, "backend.num_threads", "must be >= 1");
}

/// Joining and localising in saved sessions.
void ValidateSession(const SessionConfig& s, const std::string& src) {
  Require(s.connect_min_loops >= 1, src, "session.connect_min_loops", "must be >= 1");
  Require(s.connect_agree_m > 0, src, "session.connect_agree_m", "must be > 0");
  Require(s.connect_agree_deg > 0, src, "session.connect_agree_deg", "must be > 0");
  Require(s.search_radius_m > 0, src, "session.search_radius_m", "must be > 0");
  Require(s.localize_lost_after_m > 0, src, "session.localize_lost_after_m", "must be > 0");
  Require(s.localize_window_keyframes >= 2, src, "session.localize_window_keyframes",
          "must be >= 2");
}

}  // namespace

void ValidateConfig(const Config& c, const std::string& src) {
  ValidateCompare(c.compare, src);
  ValidateLive(c.live, src);
  ValidateDds(c.dds, src);
  ValidateSimulator(c.simulator, src);
  ValidatePlaceRecognition(c.place_recognition, src);
  ValidateSession(c.session, src);
  ValidateSensors(c, src);
  ValidateSlam(c, src);
  ValidateImaging(c, src);
  ValidateBackend(c.backend, src);
  Require(c.gating.max_odom_speed_mps > 0, src, "gating.max_odom_speed_mps", "must be > 0");
  Require(c.gating.max_odom_turn_rate_radps > 0, src, "gating.max_odom_turn_rate_radps",
          "must be > 0");
  ValidateLimits(c, src);
}

}  // namespace uwbsar
