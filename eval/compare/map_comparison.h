// `uwbsar compare`: a SAR occupancy map against a LiDAR grid, from files to outputs.
#pragma once

#include <string>
#include <vector>

#include "core/limits_config.h"
#include "eval/compare/compare_config.h"
#include "eval/compare/grid_alignment.h"
#include "eval/compare/map_metrics.h"
#include "eval/compare/sar_image_occupancy.h"
#include "imaging/occupancy_grid.h"

namespace uwbsar {

/// How the SAR map is placed on the LiDAR grid.
struct AlignRequest {
  std::string mode = "icp";  ///< "icp": ICP from `T_lidar_sar`; "origin": identity (the map
                             ///< origins are trusted); "fixed": `T_lidar_sar` as given
  Pose2 T_lidar_sar;         ///< ICP start (icp) or the transform (fixed)
  std::string method;        ///< overrides config.icp_method when not empty
};

struct ComparisonReport {
  std::string sar_path;
  std::string lidar_path;
  OccupancyGrid sar;
  OccupancyGrid lidar;
  std::string align_mode;     ///< icp, origin or fixed
  std::string icp_method;     ///< when align_mode == icp
  AlignmentResult alignment;  ///< T_target_source = T_lidar_sar actually used
  GridComparison comparison;
  double seconds = 0.0;  ///< loading, alignment and scoring
};

/// Loads both maps (InputError naming the file on bad input), aligns and scores. The SAR
/// map is a map_server YAML, or a SAR grid YAML naming an intensity image, which becomes
/// occupancy by `rule` (sar_image_occupancy.h). Throws InputError when the maps do not
/// overlap: no observed SAR cell falls on a known LiDAR cell, before or after alignment.
/// Writes nothing. Map images declaring more than `max_image_pixels` are refused before
/// decoding.
ComparisonReport CompareMapFiles(const std::string& sar_yaml, const std::string& lidar_yaml,
                                 const AlignRequest& request, const CompareConfig& config,
                                 const SarOccupancyRule& rule = {},
                                 double max_image_pixels = LimitsConfig{}.max_map_image_pixels);

/// Writes `dir`/overlay.png then `dir`/metrics.json (each to a temporary name, renamed);
/// returns the paths. `dir` must exist.
std::vector<std::string> WriteComparisonOutputs(const ComparisonReport& report,
                                                const std::string& dir,
                                                const CompareConfig& config);

}  // namespace uwbsar
