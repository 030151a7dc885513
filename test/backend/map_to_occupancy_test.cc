// MapToOccupancy: unknown where no pixel was observed; occupied where a cell's
// strongest pixel reaches occupied_fraction of the map's reference percentile,
// else free; cells on the map's own extent, row 0 at the top.
#include <gtest/gtest.h>

#include <algorithm>
#include <vector>

#include "backend/global_map.h"

namespace uwbsar {
namespace {

constexpr std::int8_t kUnknown = OccupancyGrid::kUnknown;
constexpr std::int8_t kFree = OccupancyGrid::kFree;
constexpr std::int8_t kOccupied = OccupancyGrid::kOccupied;

/// A 10 x 10 map of 0.1 m pixels covering [0, 1] x [0, 1], all observed, value 1; with
/// 0.5 m cells: cell (0, 0) is image rows 0-4, columns 0-4 (top left).
struct Map {
  cv::Mat image = cv::Mat(10, 10, CV_32FC1, cv::Scalar(1.0f));
  cv::Mat observed = cv::Mat(10, 10, CV_8UC1, cv::Scalar(255));
  ImageGrid grid = ImageGrid::Covering(0.0, 1.0, 0.0, 1.0, 0.1);

  OccupancyGrid Occupancy(double fraction, double percentile, double cell_m = 0.5) const {
    return MapToOccupancy(image, observed, grid, cell_m, fraction, percentile);
  }
};

std::vector<std::int8_t> Cells(std::int8_t tl, std::int8_t tr, std::int8_t bl, std::int8_t br) {
  return {tl, tr, bl, br};
}

TEST(MapToOccupancyTest, CellsWithNoObservedPixelAreUnknown) {
  Map m;
  m.observed.colRange(5, 10).setTo(0);
  const OccupancyGrid occ = m.Occupancy(0.5, 100.0);
  ASSERT_EQ(occ.rows, 2);
  ASSERT_EQ(occ.cols, 2);
  EXPECT_EQ(occ.cells, Cells(kOccupied, kUnknown, kOccupied, kUnknown));
}

TEST(MapToOccupancyTest, ACellIsOccupiedWhenItsStrongestPixelReachesTheThreshold) {
  Map m;
  m.image.at<float>(2, 2) = 10.0f;  // top left
  m.image.at<float>(1, 7) = 4.0f;   // top right
  // Reference (percentile 100) = 10: threshold 4 takes the top right cell, 4.1 does not.
  EXPECT_EQ(m.Occupancy(0.4, 100.0).cells, Cells(kOccupied, kOccupied, kFree, kFree));
  EXPECT_EQ(m.Occupancy(0.41, 100.0).cells, Cells(kOccupied, kFree, kFree, kFree));
}

TEST(MapToOccupancyTest, TheReferenceIsAPercentileSoOneBrightPixelDoesNotSetIt) {
  Map m;
  m.image.at<float>(2, 2) = 1000.0f;           // one very bright scatterer, top left
  m.image(cv::Rect(5, 0, 5, 4)).setTo(10.0f);  // 20 pixels of 10, top right
  // 90th percentile of 79 x 1, 20 x 10, 1 x 1000 is 10: threshold 5.
  EXPECT_EQ(m.Occupancy(0.5, 90.0).cells, Cells(kOccupied, kOccupied, kFree, kFree));
  // The maximum as reference: threshold 500.
  EXPECT_EQ(m.Occupancy(0.5, 100.0).cells, Cells(kOccupied, kFree, kFree, kFree));
}

TEST(MapToOccupancyTest, UnobservedPixelsNeitherSetTheReferenceNorMarkACell) {
  Map m;
  m.image.at<float>(1, 7) = 10.0f;
  m.observed.rowRange(5, 10).colRange(5, 10).setTo(0);
  m.image.at<float>(7, 7) = 1000.0f;  // bottom right, not observed
  EXPECT_EQ(m.Occupancy(0.5, 100.0).cells, Cells(kFree, kOccupied, kFree, kUnknown));
}

TEST(MapToOccupancyTest, AMapWithoutEchoesIsFreeNotOccupied) {
  Map m;
  m.image.setTo(0.0f);
  EXPECT_EQ(m.Occupancy(0.5, 100.0).cells, Cells(kFree, kFree, kFree, kFree));
}

TEST(MapToOccupancyTest, RowZeroIsTheTopAndTheOriginTheBottomLeftCorner) {
  Map m;
  m.image.at<float>(0, 8) = 10.0f;  // world (0.85, 0.95)
  const OccupancyGrid occ = m.Occupancy(0.5, 100.0);
  EXPECT_NEAR(occ.origin.x_m, 0.0, 1e-12);
  EXPECT_NEAR(occ.origin.y_m, 0.0, 1e-12);
  EXPECT_DOUBLE_EQ(occ.resolution_m, 0.5);
  int row = -1, col = -1;
  ASSERT_TRUE(occ.CellOf({0.85, 0.95}, &row, &col));
  EXPECT_EQ(row, 0);
  EXPECT_EQ(col, 1);
  EXPECT_TRUE(occ.IsOccupied(row, col));
  EXPECT_TRUE(occ.IsFree(1, 0));
}

TEST(MapToOccupancyTest, ACellSizeNotDividingTheMapRoundsTheGridUp) {
  Map m;
  m.image.at<float>(9, 9) = 10.0f;  // bottom right pixel, in the partial last cell
  const OccupancyGrid occ = m.Occupancy(0.5, 100.0, 0.3);
  ASSERT_EQ(occ.rows, 4);
  ASSERT_EQ(occ.cols, 4);
  EXPECT_NEAR(occ.origin.y_m, 1.0 - 4 * 0.3, 1e-12);
  EXPECT_TRUE(occ.IsOccupied(3, 3));
  EXPECT_EQ(std::count(occ.cells.begin(), occ.cells.end(), kOccupied), 1);
}

TEST(MapToOccupancyTest, AnEmptyMapGivesNoCells) {
  const OccupancyGrid occ = MapToOccupancy(cv::Mat(), cv::Mat(), ImageGrid{}, 0.5, 0.5, 99.0);
  EXPECT_TRUE(occ.cells.empty());
  EXPECT_DOUBLE_EQ(occ.resolution_m, 0.5);
}

}  // namespace
}  // namespace uwbsar
