// Scores a SAR occupancy map against a LiDAR ground-truth grid on the LiDAR's cells.
//
// Evaluation rule (what "cells the radar observed" means):
//  1. The SAR map is moved by T_lidar_sar and resampled onto the LiDAR grid (grid_resample.h:
//     max-pooling, so resolutions may differ).
//  2. A LiDAR cell is EVALUATED when the resampled SAR value is known (not unknown/205: the
//     radar observed it) AND the LiDAR value is known (the ground truth says something).
//     SAR cells outside the LiDAR grid, or on LiDAR-unknown cells, are counted but not scored.
//  3. A cell is occupied when its value >= 65 (map_server's occupied_thresh 0.65); every other
//     known value counts as free.
// Metrics over the evaluated cells:
//  - difference_ratio: cells whose occupied/free class differs / evaluated cells (the paper's
//    "cell-wise difference = differing_pixels / total_pixels", 1397 / 16800 = 8.3 %).
//  - precision: SAR-occupied evaluated cells with a LiDAR-occupied cell within
//    `tolerance_cells` (Chebyshev: the (2t+1)^2 square) / SAR-occupied evaluated cells;
//    recall: the same from the LiDAR side; F1 = 2 P R / (P + R).
//  - paper_difference_ratio: the paper's literal rule, over EVERY cell of the SAR map's
//    rectangle (observed or not; the LiDAR cell under its centre, unknown or outside the LiDAR
//    grid counting as not occupied), occupied vs not occupied: the paper counted all
//    140 x 120 cells of its 7 m x 6 m SAR image. Reported next to the observed-cells ratio
//    because it rewards the never-observed (mostly empty) cells.
//  - iou: |SAR occ AND LiDAR occ| / |SAR occ OR LiDAR occ| (strict, no tolerance).
//  - distances: from every SAR-occupied cell centre (moved by T_lidar_sar, original
//    resolution) on an evaluated cell to the nearest LiDAR-occupied cell centre anywhere in the
//    LiDAR grid, and from every LiDAR-occupied evaluated cell to the nearest SAR-occupied cell
//    centre (PCL KD-tree); mean and 95th percentile.
#pragma once

#include <cstdint>
#include <vector>

#include "core/pose2.h"
#include "eval/compare/nearest_distances.h"
#include "imaging/occupancy_grid.h"

namespace uwbsar {

struct MapMetrics {
  int tolerance_cells = 1;
  long long sar_known_cells = 0;             ///< SAR cells that are not unknown
  long long sar_known_outside_lidar = 0;     ///< ... whose centre lies outside the LiDAR grid
  long long sar_known_on_lidar_unknown = 0;  ///< LiDAR cells SAR-known but LiDAR-unknown
  long long evaluated_cells = 0;
  long long differing_cells = 0;
  double difference_ratio = 0.0;
  long long rectangle_cells = 0;      ///< cells of the SAR map's rectangle
  long long rectangle_differing = 0;  ///< ... occupied in one map and not in the other
  double paper_difference_ratio = 0.0;
  long long sar_occupied = 0;     ///< on evaluated cells
  long long lidar_occupied = 0;   ///< on evaluated cells
  long long both_occupied = 0;    ///< strict
  long long either_occupied = 0;  ///< strict
  long long sar_matched = 0;      ///< SAR-occupied with a LiDAR-occupied cell within tolerance
  long long lidar_matched = 0;    ///< LiDAR-occupied with a SAR-occupied cell within tolerance
  double precision = 0.0;         ///< NaN when the SAR map has no occupied evaluated cell
  double recall = 0.0;            ///< NaN when the LiDAR grid has no occupied evaluated cell
  double f1 = 0.0;                ///< NaN when precision or recall is
  double iou = 0.0;               ///< NaN when neither map has an occupied evaluated cell
  DistanceStats sar_to_lidar;
  DistanceStats lidar_to_sar;
};

/// Per-cell result on the LiDAR grid, for the overlay.
struct GridComparison {
  OccupancyGrid sar_on_lidar;           ///< the SAR map resampled onto the LiDAR cells
  std::vector<std::uint8_t> evaluated;  ///< 1 where the cell is scored (rule 2)
  MapMetrics metrics;
};

GridComparison CompareOnLidarGrid(const OccupancyGrid& sar, const OccupancyGrid& lidar,
                                  const Pose2& T_lidar_sar, int tolerance_cells);

}  // namespace uwbsar
