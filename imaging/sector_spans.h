// The pixels of an image that lie inside a radar's annular FOV sector, as
// row spans computed analytically (no full-image mask, unlike the reference's
// fillPoly): per row, the sector is the outer disk cut by the two boundary
// half-planes of the wedge (convex for half-angles <= 90 deg), minus the
// inner disk, i.e. at most two column intervals.
#pragma once

#include <opencv2/core.hpp>
#include <vector>

#include "core/pose2.h"
#include "imaging/image_grid.h"

namespace uwbsar {

struct RowSpan {
  int row = 0;
  int col_begin = 0;  ///< first column inside
  int col_end = 0;    ///< one past the last column inside
};

struct SectorShape {
  double fov_half_angle_rad = 0.0;
  double min_range_m = 0.0;
  double max_range_m = 0.0;
};

/// Appends to `spans` the pixels of `grid` whose centres lie in the sector of a
/// sensor at T_grid_sensor (x along boresight). Returns the number of pixels.
long long ComputeSectorSpans(const ImageGrid& grid, const Pose2& T_grid_sensor,
                             const SectorShape& sector, std::vector<RowSpan>* spans);

/// The bounding box of `spans`, rows ascending (as ComputeSectorSpans appends them); empty for
/// none.
cv::Rect SpansBounds(const std::vector<RowSpan>& spans);

/// *acc becomes the box holding both *acc and r (an empty box adds nothing).
inline void UniteBounds(cv::Rect* acc, const cv::Rect& r) {
  *acc = acc->empty() ? r : (r.empty() ? *acc : *acc | r);
}

}  // namespace uwbsar
