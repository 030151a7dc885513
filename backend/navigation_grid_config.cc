#include "backend/navigation_grid_config.h"

#include <string>

#include "core/config_require.h"

namespace uwbsar {

using config_validation::Require;

void Validate(const NavigationGridConfig& n, const std::string& src) {
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
}

}  // namespace uwbsar
