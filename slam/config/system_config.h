// The SLAM system's configuration: the slam.* section, owned here, and SystemConfig, the
// sections the SLAM system runs on, assembled from the structs their owners declare beside
// their code (Cartographer's options-next-to-owner). Each module takes only its own
// sections; the whole file's struct, Config (slam/app_config.h), adds the rest.
#pragma once

#include <string>
#include <vector>

#include "backend/backend_config.h"
#include "backend/navigation_grid_config.h"
#include "core/limits_config.h"
#include "core/radar_config.h"
#include "frontend/gating_config.h"
#include "frontend/keyframe_config.h"
#include "frontend/place_recognition/place_recognition_config.h"
#include "imaging/enhance_config.h"
#include "imaging/image_grid.h"
#include "imaging/imaging_config.h"
#include "imaging/pulse_config.h"
#include "slam/config/place_views_config.h"

namespace uwbsar {

/// The SLAM pipeline as `uwbsar map` and live mode run it.
struct SlamConfig {
  std::string odometry_topic = "/odom";  ///< nav_msgs/Odometry topic of wheel odometry
  std::string ground_truth_topic = "/ground_truth/odom";  ///< optional, for evaluation
  double map_resolution_m = 0.01;    ///< pixel size of the global map (map.png, map_float.tif)
  double mosaic_redraw_px = 0.5;     ///< live snapshots redraw a keyframe's tile in the map
                                     ///< once it moved this many map pixels (backend/
                                     ///< incremental_mosaic.h); 0: on any move
  bool keep_tile_images = false;     ///< keep every full-resolution tile in memory after its
                                     ///< features are computed (debugging; costs ~5 MB per metre)
  bool keep_scan_profiles = false;   ///< keep every imaged scan's range profile (0.8 MB per
                                     ///< metre) for the exact map; `uwbsar map --exact` sets it
  int optimize_every_keyframes = 5;  ///< re-solve the graph once this many keyframes have
                                     ///< come since the last solve and a loop is waiting
                                     ///< (1: after every loop; 0: only at the end, like the
                                     ///< follow-on code). Bounds the solver's share of a long run
  bool keyframe_thread = true;       ///< keyframe work (features, matching, solves) on its own
                                     ///< thread, so scan imaging never waits for it; the result
                                     ///< is the same either way (false: all on the caller's thread)
  int keyframe_queue_size = 4;       ///< keyframes waiting for that thread; when full, the
                                     ///< feeding thread waits. Each holds its full-resolution
                                     ///< tile and range profiles (15-20 MB): with 16, a bag read
                                     ///< faster than features are made held 300 MB more than
                                     ///< the map (office ring, ten laps: 644 -> see docs)
  double occupancy_resolution_m = 0.05;  ///< cell size of map.pgm (map_server format)
  NavigationGridConfig navigation;       ///< map.pgm: the navigation grid's sensor model
  double occupied_fraction = 0.6;        ///< the paper's rule (`compare`): a cell is occupied
                                         ///< when its strongest map pixel
                                         ///< reaches this fraction of the reference level
                                         ///< (0.6: best F1 of the paper's real strip vs
                                         ///< LiDAR; 0.3, tuned on simulated maps, made
                                         ///< real clutter occupied)
  double occupancy_reference_percentile = 99.0;  ///< reference level: this percentile of
                                                 ///< the observed map pixels
  bool results_mcap = true;  ///< map, demo, map --resume and localize also write results.mcap
                             ///< (slam/outputs/results_mcap.h); a mapping run then keeps the
                             ///< keyframe poses of every solve (24 bytes per keyframe and solve)
  double results_mcap_sar_max_pixels = 4e6;  ///< its SAR mosaic is averaged down to at most
                                             ///< this many pixels (a 20 m x 20 m map at 1 cm)
  PlaceViewsConfig place_views;  ///< keyframes bounded by area (slam/session/place_views.h)

  template <class V>
  void Visit(V& v) {
    v("odometry_topic", odometry_topic);
    v("ground_truth_topic", ground_truth_topic);
    v("map_resolution_m", map_resolution_m);
    v("mosaic_redraw_px", mosaic_redraw_px);
    v("keep_tile_images", keep_tile_images);
    v("keep_scan_profiles", keep_scan_profiles);
    v("optimize_every_keyframes", optimize_every_keyframes);
    v("keyframe_thread", keyframe_thread);
    v("keyframe_queue_size", keyframe_queue_size);
    v("occupancy_resolution_m", occupancy_resolution_m);
    v("navigation", navigation);
    v("occupied_fraction", occupied_fraction);
    v("occupancy_reference_percentile", occupancy_reference_percentile);
    v("results_mcap", results_mcap);
    v("results_mcap_sar_max_pixels", results_mcap_sar_max_pixels);
    v("place_views", place_views);
  }
};
/// Semantic checks of slam.* (the rules joining it to radars[] are in ValidateSystemConfig); throws
/// ConfigError naming the dotted key.
void Validate(const SlamConfig& config, const std::string& source_name);

/// The core sections: what drivers, frontend, backend and session code may be given (each
/// module takes only its own sections). The whole file's struct, `Config`
/// (slam/app_config.h), adds the sections owned by higher folders (simulator, live,
/// dds, compare, session); its Visit lists every section in the file's order.
struct SystemConfig {
  PulseConfig pulse;
  std::vector<RadarConfig> radars = DefaultRadars();
  ImagingConfig imaging;
  GatingConfig gating;
  KeyframeConfig keyframe;
  EnhanceConfig enhance;
  BackendConfig backend;
  PlaceRecognitionConfig place_recognition;

  SlamConfig slam;
  LimitsConfig limits;

  template <class V>
  void Visit(V& v) {
    v("slam", slam);
    v("pulse", pulse);
    v("radars", radars);
    v("imaging", imaging);
    v("gating", gating);
    v("keyframe", keyframe);
    v("enhance", enhance);
    v("backend", backend);
    v("place_recognition", place_recognition);
    v("limits", limits);
  }
};

/// Semantic checks of every section of SystemConfig and the rules that join them, then the
/// sizes they imply against limits.*. Throws ConfigError naming the dotted key.
void ValidateSystemConfig(const SystemConfig& config, const std::string& source_name);

/// The sizes the imaging and map settings imply, against limits.* (the last step of
/// ValidateSystemConfig, slam/config/system_config_limits.cc).
void ValidateLimits(const SystemConfig& config, const std::string& source_name);

/// Throws InputError when a whole-run image on `grid` (`what`: "the strip image", "the
/// exact map") exceeds limits.max_image_pixels: checked before the image is allocated.
void CheckWholeRunImage(const ImageGrid& grid, const LimitsConfig& limits, const std::string& what);

}  // namespace uwbsar
