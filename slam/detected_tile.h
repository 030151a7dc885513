// A keyframe's detected tile: its SAR image enhanced (imaging/enhance.h, the paper's positive
// image or the magnitude, blurred) and brought to the map resolution. It is what the global map
// is made of and what the wall profiles and wall lines read, when mapping and when localising.
#pragma once

#include <opencv2/core.hpp>

#include "frontend/keyframe.h"
#include "imaging/image_grid.h"
#include "slam/app_config.h"

namespace uwbsar::slam {

/// The detected tile of `k` (CV_32FC1) and its grid in the anchor frame, at
/// config.slam.map_resolution_m (the tile's own resolution when that is finer).
void MakeDetected(const Keyframe& k, const Config& config, cv::Mat* detected, ImageGrid* grid);

}  // namespace uwbsar::slam
