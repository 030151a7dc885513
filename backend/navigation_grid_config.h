// Configuration of the navigation grid (slam.navigation): map.pgm as a planner reads it, made
// by an inverse sensor model of the side-looking radars (backend/navigation_grid.h). Part of
// the slam section (slam/config/system_config.h nests it), which owns map.pgm.
#pragma once

#include <cmath>
#include <string>

namespace uwbsar {

struct NavigationGridConfig {
  double footprint_radius_m = 0.2;   ///< the robot's disc: every cell it swept is free
  double return_fraction = 0.3;      ///< a strong return: a detected tile pixel reaching this
                                     ///< fraction of the reference level
                                     ///< (slam.occupancy_reference_percentile of all tiles)
  double ray_spacing_m = 0.02;       ///< cross-track lines cast every this much robot path
  double ray_width_m = 0.05;         ///< a line reads the strongest pixel this wide across it
  double ray_half_angle_deg = 0.0;   ///< also cast lines this far either side of boresight
                                     ///< (0: the cross-track line only)
  double ray_angle_step_deg = 5.0;   ///< angle between those lines
  double free_margin_m = 0.05;       ///< cells this close before a return are not freed (the
                                     ///< wall's leading edge, pose error)
  double wall_thickness_m = 0.05;    ///< cells this far behind the first return are occupied;
                                     ///< the rest of the line is shadow (unknown)
  bool free_without_return = false;  ///< a line with no strong return frees up to the radar's
                                     ///< max_range_m (false: such a line frees nothing)
  double log_odds_hit = 0.85;        ///< log-odds added per keyframe that saw a cell occupied
  double log_odds_miss = -0.4;       ///< ... and per keyframe that saw it free
  double log_odds_clamp = 5.0;       ///< log-odds stay within +-this
  double occupied_log_odds = 0.5;    ///< a cell at or above this is occupied ...
  double free_log_odds = -0.2;       ///< ... at or below this free, else unknown
  bool wall_ridges = true;           ///< on straight keyframes, the tile's wall ridge (the peak of
                                     ///< its profile across the path) stops every line, so a wall
                                     ///< is continuous where its image is dashed
  double ridge_max_heading_change_deg = 5.0;  ///< straight: the robot's heading within a
                                              ///< keyframe varies by at most this
  double ridge_min_contrast = 3.0;       ///< a ridge: a profile bin this many times the profile's
                                         ///< median (frontend/wall_profile.h contrast) ...
  double ridge_fraction = 0.5;           ///< ... the first bin of a side reaching this fraction of
                                         ///< that side's highest bin
  double ridge_support_fraction = 0.05;  ///< a line stops at the ridge only where the tile has
                                         ///< at least this fraction of the reference level
                                         ///< within wall_thickness_m of it (a doorway in a
                                         ///< wall stays open)

  /// The lines cast either side of boresight from each antenna position: ray_half_angle_deg
  /// over ray_angle_step_deg, rounded down (0 without a half angle). Each position casts
  /// 2 SideLines() + 1 per antenna; limits.max_navigation_rays budgets them per keyframe.
  int SideLines() const {
    if (!(ray_half_angle_deg > 0)) return 0;
    const double step_rad = ray_angle_step_deg * M_PI / 180.0;
    return static_cast<int>(std::floor(ray_half_angle_deg * M_PI / 180.0 / step_rad + 1e-9));
  }

  template <class V>
  void Visit(V& v) {
    v("footprint_radius_m", footprint_radius_m);
    v("return_fraction", return_fraction);
    v("ray_spacing_m", ray_spacing_m);
    v("ray_width_m", ray_width_m);
    v("ray_half_angle_deg", ray_half_angle_deg);
    v("ray_angle_step_deg", ray_angle_step_deg);
    v("free_margin_m", free_margin_m);
    v("wall_thickness_m", wall_thickness_m);
    v("free_without_return", free_without_return);
    v("log_odds_hit", log_odds_hit);
    v("log_odds_miss", log_odds_miss);
    v("log_odds_clamp", log_odds_clamp);
    v("occupied_log_odds", occupied_log_odds);
    v("free_log_odds", free_log_odds);
    v("wall_ridges", wall_ridges);
    v("ridge_max_heading_change_deg", ridge_max_heading_change_deg);
    v("ridge_min_contrast", ridge_min_contrast);
    v("ridge_fraction", ridge_fraction);
    v("ridge_support_fraction", ridge_support_fraction);
  }
};
/// Semantic checks of slam.navigation.*; throws ConfigError naming the dotted key. The
/// navigation rays' budget (limits.max_navigation_rays) joins sections and is checked with the
/// limits (slam/config/system_config_limits.cc).
void Validate(const NavigationGridConfig& config, const std::string& source_name);

}  // namespace uwbsar
