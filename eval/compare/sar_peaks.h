// Strong scatterers of a float SAR map as points (for `uwbsar export-pcd FLOAT.tif`).
#pragma once

#include <opencv2/core.hpp>
#include <string>
#include <vector>

#include "core/limits_config.h"
#include "eval/compare/pcd_export.h"
#include "imaging/sar_grid_metadata.h"

namespace uwbsar {

/// A float SAR map (CV_32FC1 real, or CV_32FC2 re/im) with its pixel geometry.
struct FloatSarMap {
  cv::Mat image;
  SarGridMetadata grid;
};

/// Reads a float TIFF (1 page real, 2 pages re and im) and its `_grid.yaml`; throws
/// InputError naming the file when either is unreadable or their sizes disagree.
/// A TIFF declaring more than `max_image_pixels` (all pages) is refused before decoding.
FloatSarMap LoadFloatSarMap(const std::string& tiff_path, const std::string& grid_yaml_path,
                            double max_image_pixels = LimitsConfig{}.max_map_image_pixels);

/// Local maxima of the positive image (paper mode: Re + |I|; coherent: |I|) that are the
/// strongest pixel within `radius_m` and at least `min_fraction` of the strongest pixel;
/// intensity = the positive-image value. World coordinates from the grid (row 0 = top).
std::vector<IntensityPoint> SarPeaks(const FloatSarMap& map, double min_fraction, double radius_m);

}  // namespace uwbsar
