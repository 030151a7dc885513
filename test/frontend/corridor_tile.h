// Test helper: a detected keyframe tile of a corridor (speckled walls parallel to the path) for
// the wall-profile tests.
#pragma once

#include <cmath>
#include <opencv2/core.hpp>
#include <random>
#include <vector>

#include "imaging/image_grid.h"

namespace uwbsar::testing {

/// A 5 x 5 m detected tile (1 cm pixels) in its anchor frame: speckled walls parallel to the
/// heading `heading_rad`, at the signed distances `walls_m` along its left normal, each 2 m
/// long around the anchor, over a faint noise floor.
inline cv::Mat CorridorTile(const ImageGrid& grid, double heading_rad,
                            const std::vector<double>& walls_m, unsigned seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<float> speckle(0.2f, 1.0f), floor(0.0f, 0.05f);
  std::normal_distribution<double> thickness(0.0, 0.015);
  cv::Mat tile(grid.rows, grid.cols, CV_32FC1);
  for (int r = 0; r < grid.rows; ++r) {
    for (int c = 0; c < grid.cols; ++c) tile.at<float>(r, c) = floor(rng);
  }
  const double ux = std::cos(heading_rad), uy = std::sin(heading_rad);
  const double nx = -uy, ny = ux;
  for (const double wall_m : walls_m) {
    for (double along = -1.0; along <= 1.0; along += 0.004) {
      const double across = wall_m + thickness(rng);
      const double x = along * ux + across * nx, y = along * uy + across * ny;
      const int c = static_cast<int>(std::lround(grid.XToCol(x)));
      const int r = static_cast<int>(std::lround(grid.YToRow(y)));
      if (r >= 0 && r < grid.rows && c >= 0 && c < grid.cols) tile.at<float>(r, c) += speckle(rng);
    }
  }
  return tile;
}

inline ImageGrid TileGrid() { return ImageGrid::Covering(-2.5, 2.5, -2.5, 2.5, 0.01); }

}  // namespace uwbsar::testing
