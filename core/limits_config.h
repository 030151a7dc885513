// Settings of limits.*, declared beside the code that owns them (every reader of a size; checked by
// slam/config/system_config_limits.cc); the application configuration (slam/config/system_config.h,
// slam/app_config.h) assembles the sections, and core/config_io.h reads and writes any struct with
// a Visit(). config/default.yaml documents every field; a test keeps the two in sync.
#pragma once

#include <string>

namespace uwbsar {

/// Budgets on the sizes the other settings imply (docs/refusals.md): the
/// configuration is refused before any work starts when a setting would exceed them, and
/// input files declaring larger images are refused before they are decoded.
struct LimitsConfig {
  double max_tile_pixels = 3.2e7;         ///< one keyframe image: the segment canvas at
                                          ///< imaging.pixel_size_m, a tile's footprint at
                                          ///< slam.map_resolution_m (defaults: 3.2e6 and 1.0e6)
  double max_imaging_memory_mb = 2048.0;  ///< segment canvases alive at once (tile_length_m /
                                          ///< tile_spacing_m + 1) x canvas bytes (default 39)
  double max_keyframes_per_m = 20.0;      ///< 1 / keyframe.tile_spacing_m (default 1)
  double max_range_samples = 1.0e6;     ///< radars[].num_samples x coherent_oversampling (coherent)
  double max_image_pixels = 2.0e8;      ///< a whole-run image: `image` strips, `map --exact`
  double max_map_image_pixels = 5.0e7;  ///< declared size of an image read from a file (map_server
                                        ///< maps for simulate / compare / export-pcd, float maps)
  double tile_cache_mb = 64.0;  ///< detected tiles kept decoded in memory; the others wait in
                                ///< an anonymous temporary file (slam/session/tile_store.h)
  double max_navigation_rays = 2.0e4;  ///< lines the navigation grid casts per keyframe
                                       ///< (slam.navigation: positions x radars x fan; default 202)

  double max_input_file_mb = 1024.0;  ///< a text input read whole: a TUM trajectory, a text log,
                                      ///< a g2o graph, a CSV of pair statistics, waypoints

  template <class V>
  void Visit(V& v) {
    v("max_tile_pixels", max_tile_pixels);
    v("max_imaging_memory_mb", max_imaging_memory_mb);
    v("max_keyframes_per_m", max_keyframes_per_m);
    v("max_range_samples", max_range_samples);
    v("max_image_pixels", max_image_pixels);
    v("max_map_image_pixels", max_map_image_pixels);
    v("tile_cache_mb", tile_cache_mb);
    v("max_navigation_rays", max_navigation_rays);
    v("max_input_file_mb", max_input_file_mb);
  }
};

}  // namespace uwbsar
