#include "frontend/place_recognition/place_recognition_config.h"

#include <string>

#include "core/config_require.h"

namespace uwbsar {

using config_validation::Require;

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
  Require(v.detectors.size() == 2, src, k + "validation.detectors",
          "must name exactly two detectors (the paper's: [akaze, orb])");
  Require(v.detectors[0] != v.detectors[1], src, k + "validation.detectors",
          "must name two different detectors");
  for (DetectorKind d : v.detectors) {
    Require(DetectorAvailable(d), src, k + "validation.detectors",
            std::string(DetectorName(d)) + " is not available in this build");
  }
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
  const DenseRefinementConfig& r = v.refinement;
  const std::string rk = k + "validation.refinement.";
  Require(r.near_agreement_factor >= 1 && r.near_agreement_factor <= 4, src,
          rk + "near_agreement_factor", "must be in [1, 4]");
  Require(r.search_m > 0 && r.search_m <= 0.5, src, rk + "search_m", "must be in (0, 0.5]");
  Require(r.search_deg >= 0 && r.search_deg <= 10, src, rk + "search_deg", "must be in [0, 10]");
  Require(r.step_deg > 0 && r.step_deg <= 5, src, rk + "step_deg", "must be in (0, 5]");
  Require(r.min_peak_ratio >= 1, src, rk + "min_peak_ratio", "must be >= 1");
  Require(r.min_peak_ncc > 0 && r.min_peak_ncc <= 1, src, rk + "min_peak_ncc", "must be in (0, 1]");
  Require(r.highpass_sigma_m > 0 && r.highpass_sigma_m <= 1, src, rk + "highpass_sigma_m",
          "must be in (0, 1]");
  Require(r.min_overlap_fraction > 0 && r.min_overlap_fraction <= 1, src,
          rk + "min_overlap_fraction", "must be in (0, 1]");
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

}  // namespace

void Validate(const PlaceRecognitionConfig& p, const std::string& src) {
  const std::string k = "place_recognition.";
  ValidateDetectors(p.detectors, src, k);
  ValidateMatching(p.matching, src, k);
  ValidateLoopValidation(p.validation, src, k);
  ValidateCandidates(p.candidates, src, k);
  ValidateGuided(p.guided, src, k);
  ValidatePerRadar(p.per_radar, src, k);
  Validate(p.wall_profiles, src);  // beside its struct (frontend/wall_profile_config.h)
  Validate(p.registration, src, k + "registration.");  // map_registration_config.h
}

}  // namespace uwbsar
