// Semantic checks of the SLAM system's configuration: slam.* and the rules that join the
// sections (each section's own checks are beside its struct). Each failure names the key.
#include <string>

#include "core/config_require.h"
#include "slam/config/system_config.h"

namespace uwbsar {

using config_validation::Require;

void Validate(const SlamConfig& s, const std::string& src) {
  Require(s.map_resolution_m > 0 && s.map_resolution_m <= 10, src, "slam.map_resolution_m",
          "must be in (0, 10]");
  Require(s.mosaic_redraw_px >= 0 && s.mosaic_redraw_px <= 100, src, "slam.mosaic_redraw_px",
          "must be in [0, 100]");
  Require(s.optimize_every_keyframes >= 0, src, "slam.optimize_every_keyframes", "must be >= 0");
  Require(s.keyframe_queue_size >= 1, src, "slam.keyframe_queue_size", "must be >= 1");
  Require(!s.odometry_topic.empty(), src, "slam.odometry_topic", "must not be empty");
  // A cell beyond 10 m is no map (1e9 m made a 4 x 4 grid 2e9 m away); 10 m is also the
  // coarsest grid a session file holds (slam/session/session_reader.h).
  Require(s.occupancy_resolution_m >= s.map_resolution_m && s.occupancy_resolution_m <= 10, src,
          "slam.occupancy_resolution_m", "must be in [slam.map_resolution_m, 10]");
  Require(s.occupied_fraction > 0 && s.occupied_fraction <= 1, src, "slam.occupied_fraction",
          "must be in (0, 1]");
  const NavigationGridConfig& n = s.navigation;
  const std::string k = "slam.navigation.";
  Require(n.footprint_radius_m >= 0 && n.footprint_radius_m <= 10, src, k + "footprint_radius_m",
          "must be in [0, 10]");
  Require(n.return_fraction > 0 && n.return_fraction <= 1, src, k + "return_fraction",
          "must be in (0, 1]");
  Require(n.ray_spacing_m > 0 && n.ray_spacing_m <= 10, src, k + "ray_spacing_m",
          "must be in (0, 10]");
  Require(n.ray_width_m >= 0 && n.ray_width_m <= 1, src, k + "ray_width_m", "must be in [0, 1]");
  Require(n.ray_half_angle_deg >= 0 && n.ray_half_angle_deg <= 90, src, k + "ray_half_angle_deg",
          "must be in [0, 90]");
  Require(n.ray_angle_step_deg >= 0.1 && n.ray_angle_step_deg <= 90, src, k + "ray_angle_step_deg",
          "must be in [0.1, 90]");
  Require(n.free_margin_m >= 0 && n.free_margin_m <= 1, src, k + "free_margin_m",
          "must be in [0, 1]");
  Require(n.wall_thickness_m >= 0 && n.wall_thickness_m <= 1, src, k + "wall_thickness_m",
          "must be in [0, 1]");
  Require(n.log_odds_hit > 0, src, k + "log_odds_hit", "must be > 0");
  Require(n.log_odds_miss < 0, src, k + "log_odds_miss", "must be < 0");
  Require(n.log_odds_clamp > 0, src, k + "log_odds_clamp", "must be > 0");
  Require(n.occupied_log_odds > 0, src, k + "occupied_log_odds", "must be > 0");
  Require(n.free_log_odds < 0, src, k + "free_log_odds", "must be < 0");
  // A cell's log-odds stay within the clamp (a float): a threshold at or beyond it is never
  // reached, and the grid would have no occupied (or no free) cell.
  const float clamp = static_cast<float>(n.log_odds_clamp);
  Require(n.occupied_log_odds < n.log_odds_clamp && n.occupied_log_odds <= clamp, src,
          k + "occupied_log_odds",
          "must be below " + k +
              "log_odds_clamp: log-odds never pass the clamp, so no cell would be occupied");
  Require(n.free_log_odds > -n.log_odds_clamp && n.free_log_odds >= -clamp, src,
          k + "free_log_odds",
          "must be above minus " + k +
              "log_odds_clamp: log-odds never pass the clamp, so only the robot's swept disc "
              "would be free");
  Require(n.ridge_max_heading_change_deg > 0 && n.ridge_max_heading_change_deg <= 45, src,
          k + "ridge_max_heading_change_deg", "must be in (0, 45]");
  Require(n.ridge_min_contrast >= 1, src, k + "ridge_min_contrast", "must be >= 1");
  Require(n.ridge_fraction > 0 && n.ridge_fraction <= 1, src, k + "ridge_fraction",
          "must be in (0, 1]");
  Require(n.ridge_support_fraction >= 0 && n.ridge_support_fraction <= 1, src,
          k + "ridge_support_fraction", "must be in [0, 1]");
  Require(s.occupancy_reference_percentile > 0 && s.occupancy_reference_percentile <= 100, src,
          "slam.occupancy_reference_percentile", "must be in (0, 100]");
  Require(s.results_mcap_sar_max_pixels >= 1, src, "slam.results_mcap_sar_max_pixels",
          "must be >= 1");
  const PlaceViewsConfig& v = s.place_views;
  const std::string pv = "slam.place_views.";
  Require(v.max_per_place >= 0, src, pv + "max_per_place", "must be >= 0");
  Require(v.radius_m > 0 && v.radius_m <= 100, src, pv + "radius_m", "must be in (0, 100]");
  Require(v.heading_deg > 0 && v.heading_deg <= 180, src, pv + "heading_deg",
          "must be in (0, 180]");
  Require(v.min_separation_m >= 0 && v.min_separation_m <= 1e6, src, pv + "min_separation_m",
          "must be in [0, 1e6]");
}

namespace {

/// The rules that join sections: topics (radars against slam) and the feature resolution
/// (place_recognition against imaging).
void ValidateAcrossSections(const SystemConfig& c, const std::string& src) {
  Require(c.place_recognition.detectors.feature_resolution_m == 0 ||
              c.place_recognition.detectors.feature_resolution_m >= c.imaging.pixel_size_m,
          src, "place_recognition.detectors.feature_resolution_m",
          "must be 0 or >= imaging.pixel_size_m");
  for (std::size_t i = 0; i < c.radars.size(); ++i) {
    const std::string key = RadarKey(c.radars, i) + ".topic";
    Require(c.radars[i].topic != c.slam.odometry_topic, src, key,
            "must differ from slam.odometry_topic ('" + c.slam.odometry_topic + "')");
    for (std::size_t j = 0; j < i; ++j) {
      Require(c.radars[i].topic != c.radars[j].topic, src, key,
              "must differ from " + RadarKey(c.radars, j) + ".topic");
    }
  }
}

}  // namespace

void ValidateSystemConfig(const SystemConfig& c, const std::string& src) {
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
