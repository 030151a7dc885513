// A keyframe's products besides its features: its detected tile (its SAR image enhanced,
// imaging/enhance.h, at the map's resolution), the wall profile across its path
// (frontend/wall_profile.h) and the straight walls it shows (frontend/wall_line.h). This one
// step makes them, once per keyframe, for mapping (slam/slam_system.cc: the global map, the wall
// edges and landmarks) and for localisation (slam/localization/localize_pipeline.cc: the walls that
// observe the map's landmarks) alike, so that both read the same tile the same way.
#pragma once

#include <opencv2/core.hpp>
#include <optional>
#include <vector>

#include "frontend/keyframe.h"
#include "frontend/wall_line.h"
#include "frontend/wall_profile.h"
#include "frontend/wall_profile_config.h"
#include "imaging/enhance_config.h"
#include "imaging/image_grid.h"

namespace uwbsar {

/// The settings the products read (enhance.*, slam.map_resolution_m,
/// place_recognition.wall_profiles.*) and which of the wall products the caller needs.
struct KeyframeProductsConfig {
  EnhanceConfig enhance;
  double map_resolution_m = 0.01;
  WallProfileConfig walls;
  bool wall_profile = false;  ///< make the wall profile (wall edges, wall lines)
  bool wall_lines = false;    ///< and the wall lines (wall landmarks, the map's walls)

  KeyframeProductsConfig() = default;
  /// Its settings of any configuration holding them (the SLAM system's).
  template <class Config>
  KeyframeProductsConfig(const Config& config, bool make_wall_profile, bool make_wall_lines)
      : enhance(config.enhance),
        map_resolution_m(config.slam.map_resolution_m),
        walls(config.place_recognition.wall_profiles),
        wall_profile(make_wall_profile || make_wall_lines),
        wall_lines(make_wall_lines) {}
};

struct KeyframeProducts {
  /// The detected tile (CV_32FC1) and its grid in the anchor frame, at map_resolution_m (the
  /// tile's own resolution when that is finer): what the global map is made of.
  cv::Mat detected;
  ImageGrid grid;
  /// Asked for, of a complete tile (a tile cut short shows a stretch too short to measure).
  std::optional<WallProfile> wall_profile;
  std::vector<WallLineObservation> wall_lines;  ///< likewise; none without the profile
};

/// The products of `keyframe` that `config` asks for.
KeyframeProducts MakeKeyframeProducts(const Keyframe& keyframe,
                                      const KeyframeProductsConfig& config);

/// The wall profile of a keyframe's detected tile (on `grid`, its anchor frame) across the
/// robot's heading at the tile's middle.
WallProfile KeyframeWallProfile(const Keyframe& keyframe, const cv::Mat& detected,
                                const ImageGrid& grid, const WallProfileConfig& config);

}  // namespace uwbsar
