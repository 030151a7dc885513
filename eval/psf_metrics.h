// Point-spread-function quality of a detected SAR image around a known point
// target: peak position error, -3 dB widths along range and cross-range, and
// peak-sidelobe ratio (PSLR) along both cuts. The standard SAR image-quality
// figures, used by the imaging acceptance tests and printed by `uwbsar demo`.
#pragma once

#include <opencv2/core.hpp>

#include "imaging/image_grid.h"

namespace uwbsar {

struct PsfMetrics {
  bool found = false;
  Point2 peak;  ///< sub-pixel peak position, metric
  double position_error_m = 0.0;
  double range_width_m = 0.0;  ///< -3 dB (half-power) width along the range direction
  double cross_range_width_m = 0.0;
  double pslr_db = -99.0;  ///< highest sidelobe over peak on either cut (-99 = none)
  double peak_value = 0.0;
};

/// `detected` is a non-negative CV_32FC1 amplitude image on `grid`. The range
/// direction is the unit vector from the aperture centre to the target;
/// cross-range is perpendicular to it. The peak is searched within
/// `search_radius_m` of `truth`; cuts extend `cut_half_length_m` each side.
PsfMetrics MeasurePsf(const cv::Mat& detected, const ImageGrid& grid, const Point2& truth,
                      const Point2& range_direction, double search_radius_m = 0.05,
                      double cut_half_length_m = 0.3);

}  // namespace uwbsar
