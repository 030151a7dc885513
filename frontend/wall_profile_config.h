// Configuration of wall-profile edges (place_recognition.wall_profiles): along a straight
// stretch, keyframe tiles a few metres apart see the same walls at the side of the path
// but share too little of them for features (a 2 m tile focuses a wall point only from the
// scans within about 0.6 m of it). Summed along the path, each tile gives a profile across
// it; aligning two profiles measures how far the path moved sideways between the tiles, the
// one component of the odometry that its heading drift corrupts (frontend/wall_profile.h).
// Part of the configuration (frontend/place_recognition/place_recognition_config.h includes it).
#pragma once

#include <string>

#include "frontend/wall_line_config.h"

namespace uwbsar {

struct WallProfileConfig {
  bool enabled = true;                  ///< false: no wall-profile edges (loops only)
  int min_gap = 2;                      ///< pair keyframe k with k - min_gap ...
  int max_gap = 6;                      ///< ... up to k - max_gap (tiles this far apart share no
                                        ///< scan: keyframes are tile_spacing_m apart)
  double max_heading_change_deg = 3.0;  ///< the robot's heading on every keyframe in between
                                        ///< stays within this of the first one's (straight)
  double bin_m = 0.005;                 ///< profile resolution across the path
  double half_width_m = 3.0;            ///< the profile spans this either side of the anchor
  double search_m = 0.15;               ///< sideways offset searched around the odometry's
  double min_wall_contrast = 3.0;       ///< a profile's highest bin over its floor (median): less
                                        ///< is no wall, only the imaged band's own shape
  double min_correlation = 0.8;         ///< normalised cross-correlation of the aligned profiles
  double lateral_std_m = 0.02;          ///< standard deviation of the measured offset (edge weight)
  /// With walls on both sides, the shift of the left walls alone and of the right walls alone
  /// may differ by at most this; more, and the sides saw different things (0: not checked).
  double max_side_disagreement_m = 0.07;
  WallLineConfig landmarks;  ///< walls as line landmarks instead of these edges

  template <class V>
  void Visit(V& v) {
    v("enabled", enabled);
    v("min_gap", min_gap);
    v("max_gap", max_gap);
    v("max_heading_change_deg", max_heading_change_deg);
    v("bin_m", bin_m);
    v("half_width_m", half_width_m);
    v("search_m", search_m);
    v("min_wall_contrast", min_wall_contrast);
    v("min_correlation", min_correlation);
    v("lateral_std_m", lateral_std_m);
    v("max_side_disagreement_m", max_side_disagreement_m);
    v("landmarks", landmarks);
  }
};
/// Semantic checks of place_recognition.wall_profiles.* (its landmarks included); throws
/// ConfigError naming the dotted key.
void Validate(const WallProfileConfig& config, const std::string& source_name);

}  // namespace uwbsar
