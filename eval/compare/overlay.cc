#include "eval/compare/overlay.h"

#include <algorithm>
#include <opencv2/imgproc.hpp>

#include "eval/compare/metrics_json.h"

namespace uwbsar {
namespace {

constexpr int kMarginCells = 10;
constexpr int kMaxMapWidthPx = 4000;
constexpr int kLineHeightPx = 20;
constexpr double kFontScale = 0.45;

cv::Rect CropOfKnownSar(const OccupancyGrid& sar_on_lidar) {
  int r0 = sar_on_lidar.rows, r1 = -1, c0 = sar_on_lidar.cols, c1 = -1;
  for (int r = 0; r < sar_on_lidar.rows; ++r) {
    for (int c = 0; c < sar_on_lidar.cols; ++c) {
      if (sar_on_lidar.At(r, c) == OccupancyGrid::kUnknown) continue;
      r0 = std::min(r0, r);
      r1 = std::max(r1, r);
      c0 = std::min(c0, c);
      c1 = std::max(c1, c);
    }
  }
  const cv::Rect all(0, 0, sar_on_lidar.cols, sar_on_lidar.rows);
  if (r1 < 0) return all;
  const cv::Rect box(c0 - kMarginCells, r0 - kMarginCells, c1 - c0 + 1 + 2 * kMarginCells,
                     r1 - r0 + 1 + 2 * kMarginCells);
  return box & all;
}

void Text(cv::Mat& img, const std::string& text, int x, int y) {
  cv::putText(img, text, {x, y}, cv::FONT_HERSHEY_SIMPLEX, kFontScale, cv::Scalar(0, 0, 0), 1,
              cv::LINE_AA);
}

int TextWidth(const std::string& text) {
  int baseline = 0;
  return cv::getTextSize(text, cv::FONT_HERSHEY_SIMPLEX, kFontScale, 1, &baseline).width;
}

/// One colour per cell of `crop` (lattice of the LiDAR grid), as the legend keys them.
cv::Mat ColourCells(const GridComparison& g, const OccupancyGrid& lidar, const cv::Rect& crop) {
  const OccupancyGrid& sar = g.sar_on_lidar;
  cv::Mat cells(crop.height, crop.width, CV_8UC3);
  for (int r = 0; r < crop.height; ++r) {
    for (int c = 0; c < crop.width; ++c) {
      const int gr = r + crop.y, gc = c + crop.x;
      const bool lo = lidar.IsOccupied(gr, gc);
      const bool so = sar.IsOccupied(gr, gc);
      cv::Vec3b colour = OverlayColors::NotEvaluated();
      if (g.evaluated[static_cast<std::size_t>(gr) * lidar.cols + gc]) {
        colour = lo && so ? OverlayColors::Both()
                 : so     ? OverlayColors::SarOnly()
                 : lo     ? OverlayColors::LidarOnly()
                          : OverlayColors::Free();
      } else if (lo) {
        colour = OverlayColors::LidarContext();
      } else if (so) {
        colour = OverlayColors::SarContext();
      }
      cells.at<cv::Vec3b>(r, c) = colour;
    }
  }
  return cells;
}

}  // namespace

std::vector<std::pair<cv::Vec3b, std::string>> OverlayKey() {
  return {{OverlayColors::Both(), "occupied in both"},
          {OverlayColors::SarOnly(), "SAR only (LiDAR free)"},
          {OverlayColors::LidarOnly(), "LiDAR only (SAR free)"},
          {OverlayColors::Free(), "free in both"},
          {OverlayColors::NotEvaluated(), "not scored: a map unknown"},
          {OverlayColors::LidarContext(), "LiDAR the radar did not see (not scored)"},
          {OverlayColors::SarContext(), "SAR where LiDAR is unknown (not scored)"}};
}

std::vector<std::string> OverlayScoringNote(int tolerance_cells) {
  return {
      "Scored: the cells both maps know. The radar sees a wall's face, not the cells behind it,",
      "so a SAR wall a cell off the LiDAR's is SAR only beside an unscored LiDAR line "
      "(precision and F1 allow " +
          std::to_string(tolerance_cells) + (tolerance_cells == 1 ? " cell)." : " cells).")};
}

cv::Mat RenderOverlay(const ComparisonReport& report, int pixels_per_cell) {
  const GridComparison& g = report.comparison;
  const OccupancyGrid& lidar = report.lidar;
  const OccupancyGrid& sar = g.sar_on_lidar;
  const cv::Rect crop = CropOfKnownSar(sar);
  const int scale =
      std::max(1, std::min(pixels_per_cell, kMaxMapWidthPx / std::max(1, crop.width)));

  const cv::Mat cells = ColourCells(g, lidar, crop);
  cv::Mat map;
  cv::resize(cells, map, cv::Size(crop.width * scale, crop.height * scale), 0, 0,
             cv::INTER_NEAREST);

  // Legend: colour key, the scoring note, then the summary lines.
  const std::vector<std::pair<cv::Vec3b, std::string>> key = OverlayKey();
  std::vector<std::string> lines = ComparisonSummaryLines(report);
  const std::vector<std::string> note = OverlayScoringNote(g.metrics.tolerance_cells);
  lines.insert(lines.begin(), note.begin(), note.end());
  lines.insert(lines.begin(), "SAR " + report.sar_path + "  vs  LiDAR " + report.lidar_path);
  int text_width = 0, label_width = 0;
  for (const std::string& line : lines) text_width = std::max(text_width, TextWidth(line));
  for (const auto& entry : key) label_width = std::max(label_width, TextWidth(entry.second));
  const int key_rows = 3;
  const int key_per_row = static_cast<int>((key.size() + key_rows - 1) / key_rows);
  const int key_column = label_width + 40;
  const int key_width = key_per_row * key_column;
  const int width = std::max({map.cols, text_width + 20, key_width + 20});
  const int legend_height = (key_rows + static_cast<int>(lines.size())) * kLineHeightPx + 20;
  cv::Mat out(map.rows + legend_height, width, CV_8UC3, cv::Scalar(255, 255, 255));
  map.copyTo(out(cv::Rect(0, 0, map.cols, map.rows)));
  int y = map.rows + kLineHeightPx;
  for (std::size_t i = 0; i < key.size(); ++i) {
    const int x = 10 + static_cast<int>(i % key_per_row) * key_column;
    const int ky = y + static_cast<int>(i / key_per_row) * kLineHeightPx;
    const cv::Vec3b c = key[i].first;
    cv::rectangle(out, cv::Rect(x, ky - 11, 14, 14), cv::Scalar(c[0], c[1], c[2]), cv::FILLED);
    cv::rectangle(out, cv::Rect(x, ky - 11, 14, 14), cv::Scalar(0, 0, 0), 1);
    Text(out, key[i].second, x + 20, ky);
  }
  y += key_rows * kLineHeightPx;
  for (const std::string& line : lines) {
    Text(out, line, 10, y);
    y += kLineHeightPx;
  }
  return out;
}

}  // namespace uwbsar
