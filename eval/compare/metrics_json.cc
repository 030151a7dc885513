#include "eval/compare/metrics_json.h"

#include <cmath>
#include <cstdio>
#include <nlohmann/json.hpp>

namespace uwbsar {
namespace {

constexpr double kRadToDeg = 180.0 / M_PI;

nlohmann::json Number(double v) { return std::isfinite(v) ? nlohmann::json(v) : nullptr; }

nlohmann::json Distances(const DistanceStats& s) {
  return {{"count", s.count},
          {"mean_m", Number(s.mean_m)},
          {"p95_m", Number(s.p95_m)},
          {"max_m", Number(s.max_m)}};
}

nlohmann::json Transform(const Pose2& T) {
  return {{"x_m", T.x_m}, {"y_m", T.y_m}, {"yaw_deg", T.yaw_rad * kRadToDeg}};
}

nlohmann::json Grid(const std::string& path, const OccupancyGrid& g) {
  return {{"file", path},
          {"rows", g.rows},
          {"cols", g.cols},
          {"resolution_m", g.resolution_m},
          {"origin", {g.origin.x_m, g.origin.y_m, g.origin.yaw_rad}}};
}

std::string Format(const char* fmt, double a, double b = 0.0, double c = 0.0, double d = 0.0) {
  char buf[256];
  std::snprintf(buf, sizeof(buf), fmt, a, b, c, d);
  return buf;
}

/// "0.912" or "n/a".
std::string Value(double v, const char* fmt = "%.3f") {
  return std::isfinite(v) ? Format(fmt, v) : std::string("n/a");
}

}  // namespace

std::string ComparisonToJson(const ComparisonReport& r) {
  const MapMetrics& m = r.comparison.metrics;
  const AlignmentResult& a = r.alignment;
  nlohmann::json j;
  j["sar_map"] = Grid(r.sar_path, r.sar);
  j["lidar_map"] = Grid(r.lidar_path, r.lidar);
  j["evaluation_rule"] =
      "cells of the LiDAR grid where the SAR map (moved by T_lidar_sar, max-pooled onto the "
      "LiDAR cells) is known and the LiDAR grid is known; occupied = value >= 65";
  nlohmann::json align = {{"mode", r.align_mode},
                          {"accepted", a.accepted},
                          {"reason", a.reason},
                          {"T_lidar_sar", Transform(a.T_target_source)},
                          {"T_initial", Transform(a.T_initial)}};
  if (r.align_mode == "icp") {
    align["icp"] = {{"method", r.icp_method},           {"stages", a.stages},
                    {"iterations", a.iterations},       {"source_points", a.source_points},
                    {"target_points", a.target_points}, {"inlier_fraction", a.inlier_fraction},
                    {"fitness_m2", a.fitness_m2},       {"inlier_rmse_m", a.inlier_rmse_m}};
  }
  j["alignment"] = align;
  j["cells"] = {{"sar_known", m.sar_known_cells},
                {"sar_known_outside_lidar", m.sar_known_outside_lidar},
                {"sar_known_on_lidar_unknown", m.sar_known_on_lidar_unknown},
                {"evaluated", m.evaluated_cells},
                {"differing", m.differing_cells},
                {"sar_rectangle", m.rectangle_cells},
                {"sar_rectangle_differing", m.rectangle_differing},
                {"sar_occupied", m.sar_occupied},
                {"lidar_occupied", m.lidar_occupied},
                {"both_occupied", m.both_occupied},
                {"either_occupied", m.either_occupied},
                {"sar_matched", m.sar_matched},
                {"lidar_matched", m.lidar_matched}};
  j["metrics"] = {{"difference_ratio", Number(m.difference_ratio)},
                  {"paper_difference_ratio", Number(m.paper_difference_ratio)},
                  {"tolerance_cells", m.tolerance_cells},
                  {"precision", Number(m.precision)},
                  {"recall", Number(m.recall)},
                  {"f1", Number(m.f1)},
                  {"iou", Number(m.iou)},
                  {"sar_to_lidar", Distances(m.sar_to_lidar)},
                  {"lidar_to_sar", Distances(m.lidar_to_sar)}};
  j["seconds"] = r.seconds;
  return j.dump(2);
}

std::vector<std::string> ComparisonSummaryLines(const ComparisonReport& r) {
  const MapMetrics& m = r.comparison.metrics;
  const AlignmentResult& a = r.alignment;
  const Pose2& T = a.T_target_source;
  std::vector<std::string> lines;
  std::string align = "alignment: " + r.align_mode;
  if (r.align_mode == "icp") align += " (" + r.icp_method + ")";
  align +=
      Format(", T_lidar_sar = (%.3f m, %.3f m, %.2f deg)", T.x_m, T.y_m, T.yaw_rad * kRadToDeg);
  lines.push_back(align);
  if (r.align_mode == "icp") {
    lines.push_back("ICP: " + std::string(a.accepted ? "" : "REJECTED, ") + a.reason +
                    Format("; inliers %.1f %%, rmse %.3f m, fitness %.5f m^2",
                           100.0 * a.inlier_fraction, a.inlier_rmse_m, a.fitness_m2));
  }
  lines.push_back(
      Format("cell-wise difference: %.0f / %.0f = ", static_cast<double>(m.differing_cells),
             static_cast<double>(m.evaluated_cells)) +
      Value(100.0 * m.difference_ratio, "%.1f") + " % of the observed cells; paper's rule " +
      Format("(whole SAR rectangle): %.0f / %.0f = ", static_cast<double>(m.rectangle_differing),
             static_cast<double>(m.rectangle_cells)) +
      Value(100.0 * m.paper_difference_ratio, "%.1f") + " %");
  lines.push_back(Format("occupied cells (SAR %.0f, LiDAR %.0f), tolerance %.0f cell: ",
                         static_cast<double>(m.sar_occupied), static_cast<double>(m.lidar_occupied),
                         m.tolerance_cells) +
                  "precision " + Value(m.precision) + ", recall " + Value(m.recall) + ", F1 " +
                  Value(m.f1) + ", IoU " + Value(m.iou));
  lines.push_back("distance SAR->LiDAR: mean " + Value(m.sar_to_lidar.mean_m) + " m, p95 " +
                  Value(m.sar_to_lidar.p95_m) + " m; LiDAR->SAR: mean " +
                  Value(m.lidar_to_sar.mean_m) + " m, p95 " + Value(m.lidar_to_sar.p95_m) + " m");
  return lines;
}

}  // namespace uwbsar
