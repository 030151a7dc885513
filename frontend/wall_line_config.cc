#include "frontend/wall_line_config.h"

#include <string>

#include "core/config_require.h"

namespace uwbsar {

using config_validation::Require;

void Validate(const WallLineConfig& l, const std::string& src) {
  const std::string m = "place_recognition.wall_profiles.landmarks.";
  Require(l.min_peak_contrast >= 1, src, m + "min_peak_contrast", "must be >= 1");
  Require(l.min_distance_m >= 0, src, m + "min_distance_m", "must be >= 0");
  Require(l.max_lines_per_side >= 1, src, m + "max_lines_per_side", "must be >= 1");
  Require(l.strips >= 3, src, m + "strips", "must be >= 3");
  Require(l.min_strips >= 3 && l.min_strips <= l.strips, src, m + "min_strips",
          "must be in [3, strips]");
  Require(l.band_m > 0, src, m + "band_m", "must be > 0");
  Require(l.max_fit_rms_m > 0, src, m + "max_fit_rms_m", "must be > 0");
  Require(l.offset_std_m > 0, src, m + "offset_std_m", "must be > 0");
  Require(l.angle_std_deg > 0, src, m + "angle_std_deg", "must be > 0");
  Require(l.gate_offset_m > 0, src, m + "gate_offset_m", "must be > 0");
  Require(l.gate_angle_deg > 0 && l.gate_angle_deg < 45, src, m + "gate_angle_deg",
          "must be in (0, 45)");
  Require(l.max_gap >= 1, src, m + "max_gap", "must be >= 1");
  Require(l.min_observations >= 2, src, m + "min_observations", "must be >= 2");
}

}  // namespace uwbsar
