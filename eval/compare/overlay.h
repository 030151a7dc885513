// overlay.png: the LiDAR grid drawn over the SAR map on the LiDAR's cells (the paper's
// comparison figure), with a colour key and the metrics underneath.
#pragma once

#include <opencv2/core.hpp>
#include <string>
#include <utility>
#include <vector>

#include "eval/compare/map_comparison.h"

namespace uwbsar {

/// Colours (BGR) of the overlay, shared with tests.
struct OverlayColors {
  static cv::Vec3b Both() { return {0, 160, 0}; }             ///< occupied in both maps
  static cv::Vec3b SarOnly() { return {40, 40, 230}; }        ///< occupied in the SAR map only
  static cv::Vec3b LidarOnly() { return {230, 130, 0}; }      ///< occupied in the LiDAR grid only
  static cv::Vec3b Free() { return {255, 255, 255}; }         ///< evaluated, free in both
  static cv::Vec3b LidarContext() { return {150, 120, 90}; }  ///< LiDAR-occupied, not evaluated
  static cv::Vec3b SarContext() { return {140, 140, 220}; }   ///< SAR-occupied, not evaluated
  static cv::Vec3b NotEvaluated() { return {205, 205, 205}; }
};

/// The overlay's colour key: each colour with what it means, in the legend's order.
std::vector<std::pair<cv::Vec3b, std::string>> OverlayKey();

/// The legend's lines on which cells are scored: why a SAR wall can show as "SAR only" beside
/// a LiDAR line that is not scored (the radar sees a wall's face, not the cells behind it).
std::vector<std::string> OverlayScoringNote(int tolerance_cells);

/// The map part covers the bounding box of the SAR map's known cells on the LiDAR grid plus a
/// margin (the whole grid if none); each cell is `pixels_per_cell` pixels square (reduced so
/// the map stays <= 4000 pixels wide). Row 0 is the top (largest y), like the map images.
cv::Mat RenderOverlay(const ComparisonReport& report, int pixels_per_cell);

}  // namespace uwbsar
