#include "frontend/keyframe_products.h"

#include <algorithm>
#include <cmath>
#include <opencv2/imgproc.hpp>

#include "imaging/enhance.h"

namespace uwbsar {
namespace {

/// The detected tile of `k` and its grid, at `resolution_m` (the tile's own when finer).
void MakeDetected(const Keyframe& k, const EnhanceConfig& enhance, double resolution_m,
                  cv::Mat* detected, ImageGrid* grid) {
  const cv::Mat full = EnhancedFloat(k.image, enhance);
  const double factor = resolution_m / k.grid.resolution_m;
  *grid = k.grid;
  if (factor <= 1.0 + 1e-9) {
    *detected = full;
    return;
  }
  const int cols = std::max(1, static_cast<int>(std::lround(k.grid.cols / factor)));
  const int rows = std::max(1, static_cast<int>(std::lround(k.grid.rows / factor)));
  cv::resize(full, *detected, cv::Size(cols, rows), 0, 0, cv::INTER_AREA);
  *grid = k.grid.Resized(cols, rows);
}

}  // namespace

WallProfile KeyframeWallProfile(const Keyframe& keyframe, const cv::Mat& detected,
                                const ImageGrid& grid, const WallProfileConfig& config) {
  return ComputeWallProfile(
      detected, grid, keyframe.T_world_robot.yaw_rad - keyframe.T_world_anchor.yaw_rad, config);
}

KeyframeProducts MakeKeyframeProducts(const Keyframe& keyframe,
                                      const KeyframeProductsConfig& config) {
  KeyframeProducts p;
  MakeDetected(keyframe, config.enhance, config.map_resolution_m, &p.detected, &p.grid);
  if (!config.wall_profile || !keyframe.complete || p.detected.empty()) return p;
  p.wall_profile = KeyframeWallProfile(keyframe, p.detected, p.grid, config.walls);
  // The lines start from the profile's walls: the profile is made once for both.
  if (config.wall_lines)
    p.wall_lines = FindWallLines(p.detected, p.grid, *p.wall_profile, config.walls);
  return p;
}

}  // namespace uwbsar
