// Test helper: a detected keyframe tile of a corridor (speckled walls parallel to the path, or
// at an angle to it) for the wall-profile and wall-line tests.
#pragma once

#include <cmath>
#include <opencv2/core.hpp>
#include <random>
#include <vector>

#include "imaging/image_grid.h"

namespace uwbsar::testing {

/// Draws a faint noise floor and speckled walls into a tile, from one random sequence.
class SpeckledWalls {
 public:
  SpeckledWalls(const ImageGrid& grid, unsigned seed)
      : grid_(grid), rng_(seed), tile_(grid.rows, grid.cols, CV_32FC1) {
    std::uniform_real_distribution<float> floor(0.0f, 0.05f);
    for (int r = 0; r < grid.rows; ++r) {
      for (int c = 0; c < grid.cols; ++c) tile_.at<float>(r, c) = floor(rng_);
    }
  }

  /// A wall running along the unit direction (ux, uy), at `across_m` from the anchor along its
  /// left normal (-uy, ux), over [begin_m, end_m] along (ux, uy); a point every 4 mm, spread
  /// across it by a 1.5 cm standard deviation.
  void Add(double ux, double uy, double across_m, double begin_m, double end_m) {
    const double nx = -uy, ny = ux;
    for (double along = begin_m; along <= end_m; along += 0.004) {
      const double across = across_m + thickness_(rng_);
      const double x = along * ux + across * nx, y = along * uy + across * ny;
      const int c = static_cast<int>(std::lround(grid_.XToCol(x)));
      const int r = static_cast<int>(std::lround(grid_.YToRow(y)));
      if (r >= 0 && r < grid_.rows && c >= 0 && c < grid_.cols) {
        tile_.at<float>(r, c) += speckle_(rng_);
      }
    }
  }

  const cv::Mat& tile() const { return tile_; }

 private:
  ImageGrid grid_;
  std::mt19937 rng_;
  std::uniform_real_distribution<float> speckle_{0.2f, 1.0f};
  std::normal_distribution<double> thickness_{0.0, 0.015};
  cv::Mat tile_;
};

/// A 5 x 5 m detected tile (1 cm pixels) in its anchor frame: speckled walls at the signed
/// distances `walls_m` from the anchor, each 2 m long around the anchor, over a faint noise
/// floor. The walls run along heading_rad + angle_rad: parallel to the path of heading
/// `heading_rad` when angle_rad is 0, otherwise turned by angle_rad about the anchor (a wall's
/// distance is then along the left normal of its own direction).
inline cv::Mat CorridorTile(const ImageGrid& grid, double heading_rad,
                            const std::vector<double>& walls_m, unsigned seed,
                            double angle_rad = 0.0) {
  SpeckledWalls walls(grid, seed);
  const double direction_rad = heading_rad + angle_rad;
  for (const double wall_m : walls_m) {
    walls.Add(std::cos(direction_rad), std::sin(direction_rad), wall_m, -1.0, 1.0);
  }
  return walls.tile();
}

inline ImageGrid TileGrid() { return ImageGrid::Covering(-2.5, 2.5, -2.5, 2.5, 0.01); }

}  // namespace uwbsar::testing
