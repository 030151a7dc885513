// Wall profiles: the sideways offset between two keyframes of one straight stretch,
// measured from their tiles (place_recognition.wall_profiles, frontend/wall_profile_config.h).
//
// A side-looking radar images the walls beside the path. Summing a detected tile along the
// robot's heading gives a profile across the path (walls are its peaks); two tiles of the
// same corridor, metres apart, show the same walls at the same distances, shifted by how far
// the robot moved sideways between them. That shift is what the odometry's heading drift
// gets wrong (a 0.003 rad/m drift bows a 13 m corridor by 6 cm), and what loops at the ends
// of a long tour cannot observe. Only the sideways component is measured: along the path a
// wall is featureless, and the relative heading is left to the odometry.
#pragma once

#include <opencv2/core.hpp>
#include <string>
#include <vector>

#include "frontend/wall_profile_config.h"
#include "imaging/image_grid.h"

namespace uwbsar {

/// One tile's profile across the path, in its anchor frame.
struct WallProfile {
  double heading_rad = 0.0;  ///< the robot's heading in the anchor frame (the path direction)
  double bin_m = 0.005;
  /// bins[b] sums the tile over the line at signed offset (b + 0.5) * bin_m - half_width_m
  /// from the anchor along the path's left normal (-sin h, cos h), less the floor (the median
  /// of the imaged bins), clipped at 0.
  std::vector<float> bins;
  double contrast = 0.0;  ///< the highest bin over the floor, before the floor was removed
  double floor = 0.0;     ///< the floor that was removed (0: nothing imaged)

  double half_width_m() const { return 0.5 * bin_m * static_cast<double>(bins.size()); }
};

/// The profile of a detected tile (CV_32FC1, non-negative; `grid` in the anchor frame) for a
/// robot heading `heading_rad` in that frame.
WallProfile ComputeWallProfile(const cv::Mat& detected, const ImageGrid& grid, double heading_rad,
                               const WallProfileConfig& config);

struct WallProfileAlignment {
  bool accepted = false;
  double offset_m = 0.0;     ///< anchor b's offset from anchor a along a's left normal
  double correlation = 0.0;  ///< normalised cross-correlation at the best shift
  /// |left - right| of the two sides aligned alone, where both show walls (else 0)
  double side_disagreement_m = 0.0;
  std::string reason;  ///< why not accepted
};

/// Aligns `b` to `a` within config.search_m of `predicted_offset_m` (b's anchor offset from
/// a's along a's left normal, from the odometry): the shift with the largest normalised
/// cross-correlation, refined below a bin by a parabola. Refused when either profile has no
/// wall (contrast below config.min_wall_contrast). Accepted when the correlation reaches
/// config.min_correlation and the peak lies inside the searched range (a peak on its edge means
/// the true shift may lie outside it), and, where both profiles show walls on both sides of the
/// path (each side's highest bin at least min_wall_contrast x the floor), the left walls aligned
/// alone and the right walls aligned alone differ by at most config.max_side_disagreement_m (0:
/// not checked). The profiles must have the same bin size and extent.
WallProfileAlignment AlignWallProfiles(const WallProfile& a, const WallProfile& b,
                                       double predicted_offset_m, const WallProfileConfig& config);

}  // namespace uwbsar
