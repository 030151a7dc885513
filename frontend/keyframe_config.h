// Settings of keyframe.*, declared beside the code that owns them (frontend/keyframe_builder.h);
// the application configuration (slam/config/system_config.h, slam/app_config.h) assembles the
// sections, and core/config_io.h reads and writes any struct with a Visit(). config/default.yaml
// documents every field; a test keeps the two in sync.
#pragma once

#include <string>

namespace uwbsar {

/// Keyframe tiles: overlapping SAR images of L metres of path (the paper's regions).
struct KeyframeConfig {
  double tile_length_m = 2.0;   ///< path length imaged into one tile (paper: 400 px = 2 m)
  double tile_spacing_m = 1.0;  ///< path between tile starts (paper: 1 m step); tile_length_m
                                ///< must be a whole multiple of it
  double margin_m = 0.25;       ///< extra border around the sensors' reach, in the anchor frame

  template <class V>
  void Visit(V& v) {
    v("tile_length_m", tile_length_m);
    v("tile_spacing_m", tile_spacing_m);
    v("margin_m", margin_m);
  }
};
/// Semantic checks of keyframe.*; throws ConfigError naming the dotted key.
void Validate(const KeyframeConfig& config, const std::string& source_name);

}  // namespace uwbsar
