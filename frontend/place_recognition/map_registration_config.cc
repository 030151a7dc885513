#include "frontend/place_recognition/map_registration_config.h"

#include "core/config_require.h"

namespace uwbsar {

using config_validation::Require;

void Validate(const MapRegistrationConfig& r, const std::string& src, const std::string& k) {
  Require(r.resolution_m > 0 && r.resolution_m <= 0.2, src, k + "resolution_m",
          "must be in (0, 0.2]");
  Require(r.white_percentile > 50 && r.white_percentile <= 100, src, k + "white_percentile",
          "must be in (50, 100]");
  Require(r.max_map_tiles >= 1 && r.max_map_tiles <= 16, src, k + "max_map_tiles",
          "must be in [1, 16]");
  Require(r.max_centre_distance_m > 0 && r.max_centre_distance_m <= 20, src,
          k + "max_centre_distance_m", "must be in (0, 20]");
  Require(r.search_m > 0 && r.search_m <= 1, src, k + "search_m", "must be in (0, 1]");
  Require(r.search_deg >= 0 && r.search_deg <= 10, src, k + "search_deg", "must be in [0, 10]");
  Require(r.step_deg > 0 && r.step_deg <= 5, src, k + "step_deg", "must be in (0, 5]");
  Require(r.min_peak_ncc > 0 && r.min_peak_ncc <= 1, src, k + "min_peak_ncc", "must be in (0, 1]");
  Require(r.min_peak_ratio >= 1, src, k + "min_peak_ratio", "must be >= 1");
  Require(r.highpass_sigma_m > 0 && r.highpass_sigma_m <= 1, src, k + "highpass_sigma_m",
          "must be in (0, 1]");
  Require(r.min_overlap_fraction > 0 && r.min_overlap_fraction <= 1, src,
          k + "min_overlap_fraction", "must be in (0, 1]");
  Require(r.sigma_xy_m > 0, src, k + "sigma_xy_m", "must be > 0");
  Require(r.sigma_yaw_deg > 0, src, k + "sigma_yaw_deg", "must be > 0");
}

}  // namespace uwbsar
