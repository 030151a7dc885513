#include "imaging/enhance_config.h"

#include <set>
#include <string>

#include "core/config_require.h"

namespace uwbsar {

using config_validation::Require;

void Validate(const EnhanceConfig& e, const std::string& src) {
  Require(e.blur_sigma_px >= 0, src, "enhance.blur_sigma_px", "must be >= 0");
  Require(e.display_range_db > 0, src, "enhance.display_range_db", "must be > 0");
  static const std::set<std::string> kColormaps = {"gray",    "inferno", "jet",
                                                   "viridis", "magma",   "hot"};
  Require(kColormaps.count(e.colormap) > 0, src, "enhance.colormap",
          "must be one of gray, inferno, jet, viridis, magma, hot");
}

}  // namespace uwbsar
