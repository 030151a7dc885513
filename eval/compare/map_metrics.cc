#include "eval/compare/map_metrics.h"

#include <cmath>
#include <limits>
#include <opencv2/imgproc.hpp>

#include "eval/compare/grid_alignment.h"
#include "eval/compare/grid_resample.h"

namespace uwbsar {
namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

double Ratio(long long num, long long den) {
  return den > 0 ? static_cast<double>(num) / static_cast<double>(den) : kNaN;
}

/// 255 where the cell is occupied.
cv::Mat OccupiedMask(const OccupancyGrid& g) {
  cv::Mat mask(g.rows, g.cols, CV_8U, cv::Scalar(0));
  for (int r = 0; r < g.rows; ++r) {
    for (int c = 0; c < g.cols; ++c) {
      if (g.IsOccupied(r, c)) mask.at<std::uint8_t>(r, c) = 255;
    }
  }
  return mask;
}

cv::Mat Dilate(const cv::Mat& mask, int tolerance_cells) {
  if (tolerance_cells <= 0) return mask.clone();
  cv::Mat out;
  const int k = 2 * tolerance_cells + 1;
  cv::dilate(mask, out, cv::getStructuringElement(cv::MORPH_RECT, cv::Size(k, k)));
  return out;
}

/// Per-cell counts over the cells both grids know (the SAR map resampled onto the LiDAR
/// grid); marks them in out->evaluated.
void CountEvaluatedCells(const OccupancyGrid& lidar, int tolerance_cells, GridComparison* out) {
  const OccupancyGrid& s = out->sar_on_lidar;
  MapMetrics& m = out->metrics;
  const cv::Mat sar_occ = OccupiedMask(s);
  const cv::Mat lidar_occ = OccupiedMask(lidar);
  const cv::Mat sar_near = Dilate(sar_occ, tolerance_cells);
  const cv::Mat lidar_near = Dilate(lidar_occ, tolerance_cells);
  out->evaluated.assign(lidar.cells.size(), 0);
  for (int r = 0; r < lidar.rows; ++r) {
    for (int c = 0; c < lidar.cols; ++c) {
      const std::size_t i = static_cast<std::size_t>(r) * lidar.cols + c;
      if (s.cells[i] == OccupancyGrid::kUnknown) continue;
      if (lidar.cells[i] == OccupancyGrid::kUnknown) {
        ++m.sar_known_on_lidar_unknown;
        continue;
      }
      out->evaluated[i] = 1;
      ++m.evaluated_cells;
      const bool so = sar_occ.at<std::uint8_t>(r, c) != 0;
      const bool lo = lidar_occ.at<std::uint8_t>(r, c) != 0;
      if (so != lo) ++m.differing_cells;
      m.sar_occupied += so;
      m.lidar_occupied += lo;
      m.both_occupied += so && lo;
      m.either_occupied += so || lo;
      m.sar_matched += so && lidar_near.at<std::uint8_t>(r, c) != 0;
      m.lidar_matched += lo && sar_near.at<std::uint8_t>(r, c) != 0;
    }
  }
}

// The paper's rule: every cell of the SAR rectangle (the paper: all 140 x 120 cells of its
// 7 m x 6 m image, also those beyond the LiDAR grid), unknown counted as not occupied; the
// LiDAR cell under each SAR cell centre, none (= not occupied) outside the LiDAR grid.
void CountPaperRectangle(const OccupancyGrid& sar, const OccupancyGrid& lidar,
                         const Pose2& T_lidar_sar, MapMetrics* m) {
  for (int sr = 0; sr < sar.rows; ++sr) {
    for (int sc = 0; sc < sar.cols; ++sc) {
      int r = 0, c = 0;
      const bool lidar_occupied =
          lidar.CellOf(T_lidar_sar * sar.CellCenter(sr, sc), &r, &c) && lidar.IsOccupied(r, c);
      ++m->rectangle_cells;
      m->rectangle_differing += sar.IsOccupied(sr, sc) != lidar_occupied;
    }
  }
}

// Distances at the SAR map's own resolution, so they are not quantised by resampling.
void SummarizeNearestDistances(const OccupancyGrid& sar, const OccupancyGrid& lidar,
                               const Pose2& T_lidar_sar, const std::vector<std::uint8_t>& evaluated,
                               MapMetrics* m) {
  std::vector<Point2> sar_points_all, sar_points_eval;
  for (const Point2& p : OccupiedCellCenters(sar)) {
    const Point2 q = T_lidar_sar * p;
    sar_points_all.push_back(q);
    int r = 0, c = 0;
    if (lidar.CellOf(q, &r, &c) && evaluated[static_cast<std::size_t>(r) * lidar.cols + c]) {
      sar_points_eval.push_back(q);
    }
  }
  std::vector<Point2> lidar_points_all, lidar_points_eval;
  for (int r = 0; r < lidar.rows; ++r) {
    for (int c = 0; c < lidar.cols; ++c) {
      if (!lidar.IsOccupied(r, c)) continue;
      lidar_points_all.push_back(lidar.CellCenter(r, c));
      if (evaluated[static_cast<std::size_t>(r) * lidar.cols + c]) {
        lidar_points_eval.push_back(lidar.CellCenter(r, c));
      }
    }
  }
  m->sar_to_lidar = SummarizeDistances(NearestDistances(sar_points_eval, lidar_points_all));
  m->lidar_to_sar = SummarizeDistances(NearestDistances(lidar_points_eval, sar_points_all));
}

}  // namespace

GridComparison CompareOnLidarGrid(const OccupancyGrid& sar, const OccupancyGrid& lidar,
                                  const Pose2& T_lidar_sar, int tolerance_cells) {
  GridComparison out;
  ResampledGrid resampled = ResampleOnto(sar, T_lidar_sar, lidar);
  out.sar_on_lidar = std::move(resampled.grid);
  MapMetrics& m = out.metrics;
  m.tolerance_cells = tolerance_cells;
  m.sar_known_cells = resampled.source_known_cells;
  m.sar_known_outside_lidar = resampled.source_known_outside;
  CountEvaluatedCells(lidar, tolerance_cells, &out);
  CountPaperRectangle(sar, lidar, T_lidar_sar, &m);
  m.paper_difference_ratio = Ratio(m.rectangle_differing, m.rectangle_cells);
  m.difference_ratio = Ratio(m.differing_cells, m.evaluated_cells);
  m.precision = Ratio(m.sar_matched, m.sar_occupied);
  m.recall = Ratio(m.lidar_matched, m.lidar_occupied);
  m.f1 = std::isnan(m.precision) || std::isnan(m.recall) ? kNaN
         : m.precision + m.recall > 0 ? 2.0 * m.precision * m.recall / (m.precision + m.recall)
                                      : 0.0;
  m.iou = Ratio(m.both_occupied, m.either_occupied);
  SummarizeNearestDistances(sar, lidar, T_lidar_sar, out.evaluated, &m);
  return out;
}

}  // namespace uwbsar
