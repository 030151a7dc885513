#include "eval/compare/map_comparison.h"

#include <algorithm>
#include <chrono>
#include <sstream>

#include "core/errors.h"
#include "eval/compare/map_loading.h"
#include "eval/compare/metrics_json.h"
#include "eval/compare/overlay.h"
#include "imaging/image_io.h"

namespace uwbsar {
namespace {

/// World-frame bounding box of a grid's known cells, as text for error messages.
std::string KnownExtent(const OccupancyGrid& g) {
  double x0 = 1e300, x1 = -1e300, y0 = 1e300, y1 = -1e300;
  for (int r = 0; r < g.rows; ++r) {
    for (int c = 0; c < g.cols; ++c) {
      if (g.At(r, c) == OccupancyGrid::kUnknown) continue;
      const Point2 p = g.CellCenter(r, c);
      x0 = std::min(x0, p.x_m);
      x1 = std::max(x1, p.x_m);
      y0 = std::min(y0, p.y_m);
      y1 = std::max(y1, p.y_m);
    }
  }
  if (x0 > x1) return "no known cell";
  std::ostringstream out;
  out.precision(3);
  out << "x " << x0 << " .. " << x1 << " m, y " << y0 << " .. " << y1 << " m";
  return out.str();
}

void RequireOverlap(const ComparisonReport& r, const GridComparison& g, const char* when) {
  if (g.metrics.evaluated_cells > 0) return;
  throw InputError(r.sar_path + ": the maps do not overlap" + std::string(when) +
                   ": no observed cell of " + r.sar_path + " (" + KnownExtent(r.sar) +
                   ") lies on a known cell of " + r.lidar_path + " (" + KnownExtent(r.lidar) + ")");
}

}  // namespace

ComparisonReport CompareMapFiles(const std::string& sar_yaml, const std::string& lidar_yaml,
                                 const AlignRequest& request, const CompareConfig& config,
                                 const SarOccupancyRule& rule, double max_image_pixels) {
  const auto start = std::chrono::steady_clock::now();
  ComparisonReport r;
  r.sar_path = sar_yaml;
  r.lidar_path = lidar_yaml;
  r.sar = IsSarGridYaml(sar_yaml)
              ? SarImageToOccupancy(sar_yaml, rule, max_image_pixels)
              : LoadMapForComparison(sar_yaml, config.grey_205_unknown, max_image_pixels);
  r.lidar = LoadMapForComparison(lidar_yaml, config.grey_205_unknown, max_image_pixels);
  r.align_mode = request.mode;
  const int tolerance = config.tolerance_cells;

  // Refuse maps that do not overlap where the alignment starts: ICP cannot bridge them.
  const Pose2 T_start = request.mode == "origin" ? Pose2{} : request.T_lidar_sar;
  GridComparison initial = CompareOnLidarGrid(r.sar, r.lidar, T_start, tolerance);
  RequireOverlap(r, initial, request.mode == "icp" ? " at the initial alignment" : "");

  r.alignment.T_initial = T_start;
  r.alignment.T_target_source = T_start;
  if (request.mode == "icp") {
    CompareConfig icp_config = config;
    if (!request.method.empty()) icp_config.icp_method = request.method;
    r.icp_method = icp_config.icp_method;
    r.alignment = AlignPointSets(OccupiedCellCenters(r.sar), OccupiedCellCenters(r.lidar), T_start,
                                 icp_config);
    r.comparison = CompareOnLidarGrid(r.sar, r.lidar, r.alignment.T_target_source, tolerance);
    RequireOverlap(r, r.comparison, " after ICP");
  } else {
    r.alignment.accepted = true;
    r.alignment.reason = request.mode == "origin" ? "map origins trusted" : "transform given";
    r.comparison = std::move(initial);
  }
  r.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return r;
}

std::vector<std::string> WriteComparisonOutputs(const ComparisonReport& report,
                                                const std::string& dir,
                                                const CompareConfig& config) {
  const std::string overlay = dir + "/overlay.png";
  const std::string metrics = dir + "/metrics.json";
  WriteImageAtomic(overlay, RenderOverlay(report, config.overlay_pixels_per_cell));
  WriteTextAtomic(metrics, ComparisonToJson(report) + "\n");
  return {overlay, metrics};
}

}  // namespace uwbsar
