#include "slam/detected_tile.h"

#include <algorithm>
#include <cmath>
#include <opencv2/imgproc.hpp>

#include "imaging/enhance.h"

namespace uwbsar::slam {

void MakeDetected(const Keyframe& k, const Config& config, cv::Mat* detected, ImageGrid* grid) {
  const cv::Mat full = EnhancedFloat(k.image, config.enhance);
  const double factor = config.slam.map_resolution_m / k.grid.resolution_m;
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

}  // namespace uwbsar::slam
