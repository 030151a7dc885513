// The navigation grid: map.pgm as a planner needs it, from an inverse sensor model of
// side-looking SAR (slam.navigation, backend/navigation_grid_config.h).
//
// A side-looking radar sees across the path. Along each cross-track line from an antenna, the
// space before the first strong return in the keyframe's detected tile was crossed by the
// pulse, so it is free; the return is a surface (occupied, wall_thickness_m deep); what lies
// behind it is shadow and stays unknown unless another pose saw it. Each keyframe is one
// observation, fused into log-odds at its optimised pose, so a cell that one tile saw free and
// two saw occupied ends occupied, and a lone false return is outvoted. The cells the robot's
// own disc swept are free whatever the radar said: the robot was there. A wall ridge (a
// keyframe's profile peak across the path, frontend/wall_profile.h, found by the caller) stops
// the lines where the tile supports it, so a wall imaged as a dashed line of scatterers is a
// continuous one. The intensity rule of the paper (MapToOccupancy) stays for `compare`.
#pragma once

#include <opencv2/core.hpp>
#include <vector>

#include "backend/navigation_grid_config.h"
#include "core/pose2.h"
#include "imaging/image_grid.h"
#include "imaging/occupancy_grid.h"
#include "imaging/sensor_geometry.h"

namespace uwbsar {

/// A wall seen by one radar in one keyframe: the line {p : normal . p = offset_m}, anchor frame.
struct WallRidge {
  bool found = false;
  double normal_x = 0.0, normal_y = 1.0;  ///< unit normal
  double offset_m = 0.0;
};

/// One keyframe as the sensor model reads it.
struct NavigationKeyframe {
  const cv::Mat* detected = nullptr;  ///< CV_32FC1, non-negative; 0 = not imaged
  ImageGrid grid;                     ///< its pixels, in the anchor frame
  Pose2 T_map_anchor;                 ///< optimised
  std::vector<Pose2> T_anchor_robot;  ///< the robot while the tile's scans were taken
  std::vector<WallRidge> ridges;      ///< per sensor (missing or not found: none)
};

/// The `percentile` (0, 100] of the imaged pixels of every tile: the level returns are
/// measured against (the paper's rule takes the same percentile of the mosaic).
float TileReferenceLevel(const std::vector<NavigationKeyframe>& keyframes, double percentile);

/// The navigation grid of `cell_m` cells covering every tile and the robot's path `path`
/// (map frame; its swept discs are free). Throws InputError when the grid would have more than
/// `max_cells` cells (a wild pose), std::invalid_argument on a tile that is not CV_32FC1 of its
/// grid's size.
OccupancyGrid BuildNavigationGrid(const std::vector<NavigationKeyframe>& keyframes,
                                  const std::vector<Pose2>& path,
                                  const std::vector<SensorGeometry>& sensors,
                                  const NavigationGridConfig& config, double cell_m,
                                  float reference_level, double max_cells);

}  // namespace uwbsar
