// Wall lines: the straight walls a keyframe's tile shows, each as a line (offset and angle) in
// the tile's anchor frame (place_recognition.wall_profiles.landmarks, frontend/wall_line_config.h).
//
// The wall profile (frontend/wall_profile.h) sums a whole tile across the path: it finds the
// walls but not their angle to the path. Cutting the tile into strips along the path and
// locating each wall in every strip gives the wall's offset as a function of the position along
// the path; a straight line through them is the wall. Many keyframes seeing one line keep a long
// corridor straight in the pose graph (slam/wall_landmarks.h, backend/line_landmark.h).
#pragma once

#include <opencv2/core.hpp>
#include <vector>

#include "frontend/wall_profile.h"
#include "frontend/wall_profile_config.h"
#include "imaging/image_grid.h"

namespace uwbsar {

/// One straight wall as a keyframe's tile shows it, in the tile's anchor frame: the points p of
/// the wall satisfy n . p = offset_m with n = (cos normal_rad, sin normal_rad).
/// Convention: n is the left normal of the wall's direction taken along the robot's path
/// (wall direction = heading + angle, with |angle| < 90 deg), so offset_m > 0 for a wall on the
/// path's left and < 0 on its right.
struct WallLineObservation {
  double normal_rad = 0.0;      ///< in (-pi, pi]
  double offset_m = 0.0;        ///< signed distance of the wall from the anchor along n
  double offset_std_m = 0.0;    ///< landmarks.offset_std_m and the fit's standard error
  double normal_std_rad = 0.0;  ///< landmarks.angle_std_deg and the fit's standard error
  /// Extent of the wall seen, as positions along the path direction (cos h, sin h) . p of the
  /// first and last strip centres that showed it (a strip's centre: where along it the wall's
  /// energy lies, not the strip's middle).
  double begin_m = 0.0, end_m = 0.0;
  double contrast = 0.0;   ///< the wall's peak in the whole tile's profile over its floor
  double fit_rms_m = 0.0;  ///< rms of the strips' positions about the fitted line
  int num_strips = 0;      ///< strips that showed the wall (at least config.min_strips)
};

/// The straight walls of a detected tile (CV_32FC1, non-negative, on `grid` in the anchor frame)
/// for a robot heading `heading_rad` in that frame; at most landmarks.max_lines_per_side on each
/// side of the path, strongest (highest contrast) first. The profiles use config.bin_m and
/// config.half_width_m (walls further than half_width_m from the anchor are not seen), the
/// lines config.landmarks. Throws std::invalid_argument for an image of another type or size.
///
/// Method: the whole tile's profile across the path gives the walls' offsets (its peaks, at
/// least landmarks.min_peak_contrast over its floor and landmarks.min_distance_m from the
/// anchor). Around each, +-2 bands, one pass over those pixels sums the tile into cells along the
/// path x bins across it. The along-path extent in which the wall shows (4 x strips segments of
/// the band's imaged length, each tested for a peak) is cut into landmarks.strips strips, which
/// together must span at least a quarter of that length. In each strip the wall lies at its
/// profile's peak within +-band_m, at least min_peak_contrast over the lower quartile of the
/// +-2 bands (a radar's wall is blurred over about a band), refined to the centroid above that
/// floor within +-band_m / 2; its position along the path is where its energy lies. A line
/// through at least landmarks.min_strips strips, weighted by their wall energy, with an rms
/// about it of at most landmarks.max_fit_rms_m, is the wall: a step in the wall puts the strips
/// off one line and the wall is refused, not averaged. The standard deviations combine the
/// configured ones with the fit's standard errors (a strip's variance at least a bin's square).
std::vector<WallLineObservation> FindWallLines(const cv::Mat& detected, const ImageGrid& grid,
                                               double heading_rad, const WallProfileConfig& config);

/// The same with the tile's profile already computed (ComputeWallProfile of `detected` at
/// profile.heading_rad with `config`), as the wall edges need it too.
std::vector<WallLineObservation> FindWallLines(const cv::Mat& detected, const ImageGrid& grid,
                                               const WallProfile& profile,
                                               const WallProfileConfig& config);

}  // namespace uwbsar
