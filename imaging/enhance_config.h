// Settings of enhance.*, declared beside the code that owns them (imaging/enhance.h); the
// application configuration (slam/config/system_config.h, slam/app_config.h) assembles the
// sections, and core/config_io.h reads and writes any struct with a Visit(). config/default.yaml
// documents every field; a test keeps the two in sync.
#pragma once

#include <string>

namespace uwbsar {

/// Image enhancement for display and features (paper section "UWB SAR Imaging").
struct EnhanceConfig {
  double blur_sigma_px = 2.0;        ///< Gaussian blur of the positive image
  double display_range_db = 30.0;    ///< dynamic range of log-magnitude display (coherent)
  std::string colormap = "inferno";  ///< PNG colour map: gray, inferno, jet, viridis, magma, hot

  template <class V>
  void Visit(V& v) {
    v("blur_sigma_px", blur_sigma_px);
    v("display_range_db", display_range_db);
    v("colormap", colormap);
  }
};
/// Semantic checks of enhance.*; throws ConfigError naming the dotted key.
void Validate(const EnhanceConfig& config, const std::string& source_name);

}  // namespace uwbsar
