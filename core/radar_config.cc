#include "core/radar_config.h"

#include <string>
#include <vector>

#include "core/config_require.h"

namespace uwbsar {

using config_validation::Require;

void Validate(const std::vector<RadarConfig>& radars, const std::string& src) {
  Require(!radars.empty(), src, "radars", "must list at least one radar");
  for (std::size_t i = 0; i < radars.size(); ++i) {
    const RadarConfig& r = radars[i];
    const std::string k = RadarKey(radars, i) + ".";
    Require(r.fov_half_angle_deg > 0 && r.fov_half_angle_deg <= 90, src, k + "fov_half_angle_deg",
            "must be in (0, 90]");
    Require(r.min_range_m >= 0, src, k + "min_range_m", "must be >= 0");
    Require(r.max_range_m > r.min_range_m, src, k + "max_range_m", "must exceed min_range_m");
    Require(r.num_samples > 1, src, k + "num_samples", "must be > 1");
    Require(r.zero_leading_samples >= 0 && r.zero_leading_samples < r.num_samples, src,
            k + "zero_leading_samples", "must be in [0, num_samples)");
  }
}

}  // namespace uwbsar
