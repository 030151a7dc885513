// Maps for the comparison tests: the seed_lab LiDAR grid, moved copies, map_server files.
#pragma once

#include <string>

#include "imaging/occupancy_grid.h"

namespace uwbsar::testing {

/// ../shared/data/maps/seed_lab/my_map.yaml (the paper's LiDAR grid, 320 x 82 cells at 0.05 m), as
/// the comparison reads it (grey 205 unknown).
std::string SeedLabYaml();
OccupancyGrid SeedLabGrid();

/// The grid's content moved rigidly by T (p' = T p) and rasterised again on a new
/// axis-aligned grid of `resolution_m` (0: the grid's own); each new cell takes the maximum of
/// the original cells at a few sample points inside it (unknown outside the original).
OccupancyGrid RasterizedCopy(const OccupancyGrid& grid, const Pose2& T, double resolution_m = 0);

/// A grid of `rows` x `cols` free cells at `resolution_m`, origin at `origin`.
OccupancyGrid FreeGrid(int rows, int cols, double resolution_m, const Pose2& origin = {});

/// Writes `dir`/`name`.pgm (P5, trinary: 0 occupied, 254 free, 205 unknown) and
/// `dir`/`name`.yaml; returns the YAML path.
std::string WriteMapServer(const OccupancyGrid& grid, const std::string& dir,
                           const std::string& name);

/// A fresh empty folder under the temporary directory.
std::string FreshDir(const std::string& name);

}  // namespace uwbsar::testing
