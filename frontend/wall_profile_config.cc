#include "frontend/wall_profile_config.h"

#include <string>

#include "core/config_require.h"

namespace uwbsar {

using config_validation::Require;

void Validate(const WallProfileConfig& w, const std::string& src) {
  const std::string k = "place_recognition.wall_profiles.";
  Require(w.min_gap >= 1, src, k + "min_gap", "must be >= 1");
  Require(w.max_gap >= w.min_gap && w.max_gap <= 100, src, k + "max_gap",
          "must be in [wall_profiles.min_gap, 100]");
  Require(w.max_heading_change_deg > 0 && w.max_heading_change_deg <= 45, src,
          k + "max_heading_change_deg", "must be in (0, 45]");
  Require(w.bin_m > 0 && w.bin_m <= 0.1, src, k + "bin_m", "must be in (0, 0.1]");
  Require(w.half_width_m >= 10 * w.bin_m && w.half_width_m / w.bin_m <= 1e5, src,
          k + "half_width_m", "must be in [10, 1e5] x wall_profiles.bin_m");
  Require(w.search_m >= w.bin_m && w.search_m < w.half_width_m, src, k + "search_m",
          "must be in [bin_m, half_width_m)");
  Require(w.min_wall_contrast >= 1, src, k + "min_wall_contrast", "must be >= 1");
  Require(w.min_correlation > 0 && w.min_correlation <= 1, src, k + "min_correlation",
          "must be in (0, 1]");
  Require(w.lateral_std_m > 0, src, k + "lateral_std_m", "must be > 0");
  Require(w.max_side_disagreement_m >= 0 && w.max_side_disagreement_m <= w.search_m * 2, src,
          k + "max_side_disagreement_m", "must be in [0, 2 x wall_profiles.search_m]");
  Validate(w.landmarks, src);
}

}  // namespace uwbsar
