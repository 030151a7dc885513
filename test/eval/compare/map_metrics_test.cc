#include "eval/compare/map_metrics.h"

#include <gtest/gtest.h>

#include <cmath>

#include "test/shared_data.h"
#include "test_maps.h"

namespace uwbsar {
namespace {

using testing::FreeGrid;

void SetOccupied(OccupancyGrid& g, int row, int col) {
  g.cells[static_cast<std::size_t>(row) * g.cols + col] = OccupancyGrid::kOccupied;
}
void SetUnknown(OccupancyGrid& g, int row, int col) {
  g.cells[static_cast<std::size_t>(row) * g.cols + col] = OccupancyGrid::kUnknown;
}

TEST(MapMetricsTest, SeedLabAgainstItselfIsPerfect) {
  UWBSAR_NEED_SEED_LAB_MAP();
  const OccupancyGrid lidar = testing::SeedLabGrid();
  const MapMetrics m = CompareOnLidarGrid(lidar, lidar, Pose2{}, 1).metrics;
  EXPECT_GT(m.evaluated_cells, 10000);
  EXPECT_GT(m.lidar_occupied, 500);
  EXPECT_EQ(m.differing_cells, 0);
  EXPECT_EQ(m.difference_ratio, 0.0);
  EXPECT_EQ(m.paper_difference_ratio, 0.0);
  EXPECT_EQ(m.rectangle_cells, lidar.rows * lidar.cols);
  EXPECT_EQ(m.precision, 1.0);
  EXPECT_EQ(m.recall, 1.0);
  EXPECT_EQ(m.f1, 1.0);
  EXPECT_EQ(m.iou, 1.0);
  EXPECT_EQ(m.sar_to_lidar.max_m, 0.0);
  EXPECT_EQ(m.lidar_to_sar.max_m, 0.0);
  EXPECT_EQ(m.sar_to_lidar.count, m.sar_occupied);
}

TEST(MapMetricsTest, OneCellShiftIsWithinToleranceButNotStrictlyEqual) {
  UWBSAR_NEED_SEED_LAB_MAP();
  const OccupancyGrid lidar = testing::SeedLabGrid();
  const Pose2 one_cell{0.05, 0.0, 0.0};
  const MapMetrics tolerant = CompareOnLidarGrid(lidar, lidar, one_cell, 1).metrics;
  EXPECT_EQ(tolerant.f1, 1.0);
  EXPECT_GT(tolerant.differing_cells, 0);
  EXPECT_LT(tolerant.iou, 0.9);
  EXPECT_LE(tolerant.sar_to_lidar.max_m, 0.05 + 1e-9);
  EXPECT_GT(tolerant.sar_to_lidar.mean_m, 0.0);
  const MapMetrics strict = CompareOnLidarGrid(lidar, lidar, one_cell, 0).metrics;
  EXPECT_LT(strict.f1, 0.9);
}

TEST(MapMetricsTest, HandCountedCellsOnlyWhereBothMapsAreKnown) {
  // 4 rows x 5 columns of 0.1 m. LiDAR: wall in column 1, column 4 unknown. SAR: row 0
  // unknown; occupied (1,1) on the wall, (1,3) two cells off it, (3,4) on LiDAR-unknown.
  OccupancyGrid lidar = FreeGrid(4, 5, 0.1);
  OccupancyGrid sar = FreeGrid(4, 5, 0.1);
  for (int r = 0; r < 4; ++r) {
    SetOccupied(lidar, r, 1);
    SetUnknown(lidar, r, 4);
  }
  for (int c = 0; c < 5; ++c) SetUnknown(sar, 0, c);
  SetOccupied(sar, 1, 1);
  SetOccupied(sar, 1, 3);
  SetOccupied(sar, 3, 4);
  const MapMetrics m = CompareOnLidarGrid(sar, lidar, Pose2{}, 1).metrics;
  EXPECT_EQ(m.sar_known_cells, 15);
  EXPECT_EQ(m.sar_known_on_lidar_unknown, 3);
  EXPECT_EQ(m.evaluated_cells, 12);  // rows 1..3, columns 0..3
  EXPECT_EQ(m.differing_cells, 3);   // (2,1), (3,1) missed; (1,3) extra
  EXPECT_DOUBLE_EQ(m.difference_ratio, 0.25);
  // Paper's rule: all 20 cells of the SAR rectangle; unknown = not occupied, so (0,1) and
  // (3,4) differ too.
  EXPECT_EQ(m.rectangle_cells, 20);
  EXPECT_EQ(m.rectangle_differing, 5);
  EXPECT_DOUBLE_EQ(m.paper_difference_ratio, 0.25);
  EXPECT_EQ(m.sar_occupied, 2);
  EXPECT_EQ(m.lidar_occupied, 3);
  EXPECT_DOUBLE_EQ(m.precision, 0.5);     // (1,3) is two cells from the wall
  EXPECT_DOUBLE_EQ(m.recall, 2.0 / 3.0);  // (3,1) is two cells from (1,1)
  EXPECT_DOUBLE_EQ(m.f1, 4.0 / 7.0);
  EXPECT_DOUBLE_EQ(m.iou, 0.25);  // both: (1,1); either: (1,1) (2,1) (3,1) (1,3)
  EXPECT_EQ(m.sar_to_lidar.count, 2);
  EXPECT_NEAR(m.sar_to_lidar.mean_m, 0.1, 1e-9);  // 0 and 0.2 m
  EXPECT_NEAR(m.sar_to_lidar.p95_m, 0.2, 1e-9);
  EXPECT_EQ(m.lidar_to_sar.count, 3);
  EXPECT_NEAR(m.lidar_to_sar.mean_m, 0.1, 1e-9);  // 0, 0.1 and 0.2 m
  EXPECT_NEAR(m.lidar_to_sar.max_m, 0.2, 1e-9);
}

TEST(MapMetricsTest, NoOccupiedSarCellLeavesPrecisionUndefined) {
  OccupancyGrid lidar = FreeGrid(3, 3, 0.1);
  SetOccupied(lidar, 1, 1);
  const OccupancyGrid sar = FreeGrid(3, 3, 0.1);
  const MapMetrics m = CompareOnLidarGrid(sar, lidar, Pose2{}, 1).metrics;
  EXPECT_TRUE(std::isnan(m.precision));
  EXPECT_EQ(m.recall, 0.0);
  EXPECT_TRUE(std::isnan(m.f1));
  EXPECT_EQ(m.iou, 0.0);
  EXPECT_EQ(m.sar_to_lidar.count, 0);
  EXPECT_TRUE(std::isnan(m.lidar_to_sar.mean_m));
  EXPECT_DOUBLE_EQ(m.difference_ratio, 1.0 / 9.0);
}

}  // namespace
}  // namespace uwbsar
