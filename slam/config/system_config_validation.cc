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
  Validate(s.navigation, src);  // beside its struct (backend/navigation_grid_config.h)
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
