#include "eval/compare/grid_resample.h"

#include <gtest/gtest.h>

#include "test/shared_data.h"
#include "test_maps.h"

namespace uwbsar {
namespace {

using testing::FreeGrid;

TEST(GridResampleTest, IdentityCopiesAnEqualGridExactly) {
  UWBSAR_NEED_SEED_LAB_MAP();
  const OccupancyGrid lidar = testing::SeedLabGrid();
  const ResampledGrid r = ResampleOnto(lidar, Pose2{}, lidar);
  EXPECT_EQ(r.grid.cells, lidar.cells);
  EXPECT_EQ(r.source_known_outside, 0);
}

TEST(GridResampleTest, FinerSourceIsMaxPooledSoAThinWallSurvives) {
  OccupancyGrid fine = FreeGrid(8, 8, 0.025);        // 0.2 m square
  fine.cells[3 * 8 + 5] = OccupancyGrid::kOccupied;  // one fine cell
  const OccupancyGrid coarse = FreeGrid(4, 4, 0.05);
  const ResampledGrid r = ResampleOnto(fine, Pose2{}, coarse);
  int occupied = 0;
  for (int row = 0; row < 4; ++row) {
    for (int col = 0; col < 4; ++col) occupied += r.grid.IsOccupied(row, col);
  }
  EXPECT_EQ(occupied, 1);
  EXPECT_TRUE(r.grid.IsOccupied(1, 2));  // fine (row 3, col 5) lies in coarse (1, 2)
}

TEST(GridResampleTest, CoarserSourceFillsEveryTargetCellItCovers) {
  OccupancyGrid coarse = FreeGrid(2, 2, 0.1);
  coarse.cells[0] = OccupancyGrid::kOccupied;  // top-left 0.1 m cell
  const OccupancyGrid fine = FreeGrid(4, 4, 0.05);
  const ResampledGrid r = ResampleOnto(coarse, Pose2{}, fine);
  for (int row = 0; row < 4; ++row) {
    for (int col = 0; col < 4; ++col) {
      EXPECT_EQ(r.grid.IsOccupied(row, col), row < 2 && col < 2) << row << "," << col;
      EXPECT_NE(r.grid.At(row, col), OccupancyGrid::kUnknown);
    }
  }
}

TEST(GridResampleTest, TransformMovesContentAndCountsCellsOutside) {
  OccupancyGrid source = FreeGrid(4, 4, 0.05);
  source.cells[3 * 4 + 0] = OccupancyGrid::kOccupied;  // bottom-left cell, centre (0.025, 0.025)
  const OccupancyGrid target = FreeGrid(4, 4, 0.05);
  // Shift by two cells right: the two right-most source columns fall outside the target.
  const ResampledGrid r = ResampleOnto(source, Pose2{0.1, 0.0, 0.0}, target);
  EXPECT_TRUE(r.grid.IsOccupied(3, 2));
  EXPECT_EQ(r.grid.At(3, 0), OccupancyGrid::kUnknown);
  EXPECT_EQ(r.source_known_cells, 16);
  EXPECT_EQ(r.source_known_outside, 8);
}

}  // namespace
}  // namespace uwbsar
