#include "frontend/keyframe_config.h"

#include <cmath>
#include <string>

#include "core/config_require.h"

namespace uwbsar {

using config_validation::Require;

void Validate(const KeyframeConfig& k, const std::string& src) {
  Require(k.tile_length_m > 0, src, "keyframe.tile_length_m", "must be > 0");
  Require(k.tile_spacing_m > 0 && k.tile_spacing_m <= k.tile_length_m, src,
          "keyframe.tile_spacing_m", "must be in (0, tile_length_m]");
  const double ratio = k.tile_length_m / k.tile_spacing_m;
  Require(std::abs(ratio - std::round(ratio)) < 1e-6, src, "keyframe.tile_length_m",
          "must be a whole multiple of keyframe.tile_spacing_m");
  Require(k.margin_m >= 0, src, "keyframe.margin_m", "must be >= 0");
}

}  // namespace uwbsar
