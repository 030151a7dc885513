// The jobs behind `uwbsar compare` and `uwbsar export-pcd`: a SAR map scored against a LiDAR
// grid with its outputs (eval/compare/map_comparison.h), and a map written as a PCD cloud
// (eval/compare/pcd_export.h). The command line parses the flags, checks the output paths
// first (slam/outputs/output_folder.h) and prints what these return.
#pragma once

#include <cstddef>
#include <string>
#include <vector>

#include "app/app_config.h"
#include "eval/compare/map_comparison.h"

namespace uwbsar::eval {

struct CompareJobResult {
  ComparisonReport report;
  std::vector<std::string> files;          ///< the outputs written (overlay.png, metrics.json)
  std::string json;                        ///< metrics.json's document
  std::vector<std::string> summary_lines;  ///< the human summary, one line each
};

/// Loads and scores `sar_yaml` (a map_server map, or a SAR image's grid YAML made occupancy by
/// the rule of config.slam) against `lidar_yaml` (config.compare, config.limits), and only then
/// creates `out_dir` and writes overlay.png and metrics.json in it: bad input (InputError
/// naming the file, maps that do not overlap) leaves nothing. The caller checks `out_dir`
/// before (CheckOutputFolder), so an unusable folder is refused before the work.
CompareJobResult RunCompareJob(const AppConfig& config, const std::string& sar_yaml,
                               const std::string& lidar_yaml, const AlignRequest& request,
                               const std::string& out_dir);

/// True for the path of a float SAR map (.tif or .tiff, any case), which `uwbsar export-pcd`
/// exports as peaks; other maps are map_server YAML.
bool IsFloatSarMapPath(const std::string& path);

struct PcdExportResult {
  std::size_t points = 0;
  std::string what;  ///< "SAR peaks" or "occupied cells"
};

/// Writes `map` to `out_pcd` as a PCD v0.7 cloud (x y z intensity; binary or ASCII): the peaks
/// of a float SAR map (IsFloatSarMapPath; its pixel geometry from `grid_yaml`, default
/// `<prefix>_grid.yaml` beside `<prefix>_float.tif`; compare.pcd_peak_*) or the occupied cells
/// of a map_server map (`grid_yaml` unused). Maps larger than limits.max_map_image_pixels are
/// refused before decoding. The caller checks `out_pcd` before (CheckOutputFile).
PcdExportResult ExportPcdJob(const AppConfig& config, const std::string& map,
                             const std::string& grid_yaml, const std::string& out_pcd, bool binary);

}  // namespace uwbsar::eval
