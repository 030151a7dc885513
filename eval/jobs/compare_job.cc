#include "eval/jobs/compare_job.h"

#include <cctype>
#include <filesystem>

#include "eval/compare/metrics_json.h"
#include "eval/compare/pcd_export.h"
#include "eval/compare/sar_peaks.h"
#include "slam/outputs/output_folder.h"

namespace uwbsar::eval {
namespace {

/// `<prefix>_float.tif` -> `<prefix>_grid.yaml` (slam/jobs/imaging_job.cc's naming).
std::string DefaultGridYaml(const std::string& tiff) {
  const std::string stem = std::filesystem::path(tiff).stem().string();
  const std::string suffix = "_float";
  const std::string prefix =
      stem.size() > suffix.size() &&
              stem.compare(stem.size() - suffix.size(), suffix.size(), suffix) == 0
          ? stem.substr(0, stem.size() - suffix.size())
          : stem;
  return (std::filesystem::path(tiff).parent_path() / (prefix + "_grid.yaml")).string();
}

}  // namespace

CompareJobResult RunCompareJob(const AppConfig& config, const std::string& sar_yaml,
                               const std::string& lidar_yaml, const AlignRequest& request,
                               const std::string& out_dir) {
  CompareJobResult result;
  // Everything is computed before the output folder is touched: bad input leaves nothing.
  result.report =
      CompareMapFiles(sar_yaml, lidar_yaml, request, config.compare,
                      SarOccupancyRuleOf(config.slam), config.limits.max_map_image_pixels);
  slam::EnsureDirectory(out_dir);
  result.files = WriteComparisonOutputs(result.report, out_dir, config.compare);
  result.json = ComparisonToJson(result.report);
  result.summary_lines = ComparisonSummaryLines(result.report);
  return result;
}

bool IsFloatSarMapPath(const std::string& path) {
  std::string ext = std::filesystem::path(path).extension().string();
  for (char& c : ext) c = static_cast<char>(std::tolower(c));
  return ext == ".tif" || ext == ".tiff";
}

PcdExportResult ExportPcdJob(const AppConfig& config, const std::string& map,
                             const std::string& grid_yaml, const std::string& out_pcd,
                             bool binary) {
  std::vector<IntensityPoint> points;
  PcdExportResult result;
  if (IsFloatSarMapPath(map)) {
    const std::string grid = grid_yaml.empty() ? DefaultGridYaml(map) : grid_yaml;
    points = SarPeaks(LoadFloatSarMap(map, grid, config.limits.max_map_image_pixels),
                      config.compare.pcd_peak_fraction, config.compare.pcd_peak_radius_m);
    result.what = "SAR peaks";
  } else {
    points = OccupiedCellPoints(LoadOccupancyGrid(map, config.limits.max_map_image_pixels));
    result.what = "occupied cells";
  }
  WritePcd(out_pcd, points, binary);
  result.points = points.size();
  return result;
}

}  // namespace uwbsar::eval
