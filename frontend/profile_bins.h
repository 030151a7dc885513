// Projecting a tile's pixels onto a direction and spreading them over fine bins: shared by the
// wall profile (frontend/wall_profile.h) and the wall lines (frontend/wall_line.h), which both
// sum a tile across the path at a finer step than its pixels.
#pragma once

#include <algorithm>
#include <cmath>

#include "imaging/image_grid.h"

namespace uwbsar {

/// The coordinate (dx, dy) . p of the pixel centres p of `grid`: linear in column and row, so a
/// pass over the pixels needs no trigonometry.
struct GridProjection {
  GridProjection(const ImageGrid& grid, double dx, double dy)
      : at_origin_m(dx * grid.x0_m + dy * grid.y0_m),
        per_col_m(dx * grid.resolution_m),
        per_row_m(-dy * grid.resolution_m),
        footprint_m(grid.resolution_m * (std::abs(dx) + std::abs(dy))) {}

  double AtRow(int r) const { return at_origin_m + per_row_m * r; }
  double At(int c, int r) const { return AtRow(r) + per_col_m * c; }

  double at_origin_m;  ///< at the centre of pixel (0, 0)
  double per_col_m;    ///< change from one column to the next
  double per_row_m;    ///< ... and from one row to the next
  /// The width a pixel's square covers along the direction: each pixel is spread over it, so
  /// that bins finer than the pixels get no empty comb on an axis-aligned direction.
  double footprint_m;
};

/// Adds `value` spread evenly over the bin interval [lo, lo + width) (in bins, width > 0) to
/// bins[0, num_bins); what falls outside is dropped.
inline void SpreadOverBins(double lo, double width, double value, float* bins, int num_bins) {
  const double hi = lo + width, density = value / width;
  const int end = std::min(num_bins, static_cast<int>(std::ceil(hi)));
  for (int b = std::max(0, static_cast<int>(std::floor(lo))); b < end; ++b) {
    const double overlap = std::min<double>(hi, b + 1) - std::max<double>(lo, b);
    bins[b] += static_cast<float>(density * overlap);
  }
}

}  // namespace uwbsar
