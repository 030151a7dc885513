#include "eval/compare/compare_config.h"

#include <string>

#include "core/config_require.h"

namespace uwbsar {

using config_validation::Require;

void Validate(const CompareConfig& c, const std::string& src) {
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

}  // namespace uwbsar
