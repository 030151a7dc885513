// GlobalMap: tiles land at their pose on the world lattice, overlapping tiles are
// averaged, and 0 means unobserved: such pixels neither count in the average nor
// show as observed.
#include "backend/global_map.h"

#include <gtest/gtest.h>

#include <cmath>

namespace uwbsar {
namespace {

constexpr double kResM = 0.05;

/// A grid of `cols` x `rows` pixels of kResM whose pixel (0, 0) is centred on the
/// tile frame's origin (so, at an identity pose, on the world lattice).
ImageGrid TileGrid(int cols, int rows) {
  ImageGrid g;
  g.resolution_m = kResM;
  g.cols = cols;
  g.rows = rows;
  return g;
}

cv::Mat Constant(int cols, int rows, float value) {
  return cv::Mat(rows, cols, CV_32FC1, cv::Scalar(value));
}

/// Rendered value and observed flag at a world point.
struct Probe {
  float value;
  bool observed;
};

Probe At(const GlobalMap& map, double x_m, double y_m) {
  ImageGrid grid;
  cv::Mat observed;
  const cv::Mat image = map.Render(&grid, &observed);
  const int c = static_cast<int>(std::lround(grid.XToCol(x_m)));
  const int r = static_cast<int>(std::lround(grid.YToRow(y_m)));
  EXPECT_TRUE(grid.Contains(c, r)) << x_m << ", " << y_m;
  if (!grid.Contains(c, r)) return {0.0f, false};
  return {image.at<float>(r, c), observed.at<unsigned char>(r, c) != 0};
}

TEST(GlobalMapTest, AnEmptyMapRendersNothing) {
  GlobalMap map(kResM, 32);
  ImageGrid grid;
  cv::Mat observed;
  EXPECT_TRUE(map.Render(&grid, &observed).empty());
  EXPECT_EQ(grid.rows, 0);
  EXPECT_EQ(map.num_blocks(), 0u);
}

TEST(GlobalMapTest, RenderPixelsIsTheRenderedSizeBeforeAllocating) {
  GlobalMap map(kResM, 32);
  EXPECT_EQ(map.RenderPixels(), 0.0);
  map.AddTile(Constant(20, 20, 2.0f), TileGrid(20, 20), Pose2{});
  map.AddTile(Constant(20, 20, 2.0f), TileGrid(20, 20), Pose2{100.0, 40.0, 0.0});  // far away
  // Two blocks far apart: sparse, but the dense image is their bounding box.
  ImageGrid grid;
  cv::Mat observed;
  const cv::Mat image = map.Render(&grid, &observed);
  EXPECT_EQ(map.RenderPixels(), static_cast<double>(image.rows) * image.cols);
  EXPECT_GT(map.RenderPixels(), 100.0 / kResM * 40.0 / kResM);
}

TEST(GlobalMapTest, OverlappingTilesAreAveraged) {
  GlobalMap map(kResM, 32);
  map.AddTile(Constant(20, 20, 2.0f), TileGrid(20, 20), Pose2{});
  map.AddTile(Constant(20, 20, 4.0f), TileGrid(20, 20), Pose2{0.5, 0.0, 0.0});
  // Tile 1 covers x in [0, 0.95], tile 2 x in [0.5, 1.45]; both y in [-0.95, 0].
  EXPECT_NEAR(At(map, 0.2, -0.5).value, 2.0f, 1e-4);
  EXPECT_NEAR(At(map, 0.7, -0.5).value, 3.0f, 1e-4);
  EXPECT_NEAR(At(map, 1.2, -0.5).value, 4.0f, 1e-4);
  EXPECT_TRUE(At(map, 0.7, -0.5).observed);
}

TEST(GlobalMapTest, ZeroPixelsAreUnobservedAndNotAveragedIn) {
  GlobalMap map(kResM, 32);
  map.AddTile(Constant(20, 20, 2.0f), TileGrid(20, 20), Pose2{});
  cv::Mat half = Constant(20, 20, 4.0f);
  half.colRange(0, 10).setTo(0.0f);  // x in [0, 0.45] unobserved by the second tile
  map.AddTile(half, TileGrid(20, 20), Pose2{});
  EXPECT_NEAR(At(map, 0.1, -0.5).value, 2.0f, 1e-4);  // not (2 + 0) / 2
  EXPECT_NEAR(At(map, 0.8, -0.5).value, 3.0f, 1e-4);
}

TEST(GlobalMapTest, PixelsNoTileObservedRenderAsZeroAndUnobserved) {
  GlobalMap map(kResM, 32);
  cv::Mat tile = Constant(20, 20, 5.0f);
  tile.rowRange(10, 20).setTo(0.0f);  // y in [-0.95, -0.5] unobserved
  map.AddTile(tile, TileGrid(20, 20), Pose2{});
  const Probe seen = At(map, 0.5, -0.2);
  EXPECT_NEAR(seen.value, 5.0f, 1e-4);
  EXPECT_TRUE(seen.observed);
  const Probe unseen = At(map, 0.5, -0.8);
  EXPECT_EQ(unseen.value, 0.0f);
  EXPECT_FALSE(unseen.observed);
  // Beyond the tile, inside its allocated block (1.6 m square).
  const Probe outside = At(map, 1.3, -0.5);
  EXPECT_EQ(outside.value, 0.0f);
  EXPECT_FALSE(outside.observed);
}

TEST(GlobalMapTest, AnAllZeroTileAllocatesNoBlock) {
  GlobalMap map(kResM, 32);
  map.AddTile(Constant(20, 20, 0.0f), TileGrid(20, 20), Pose2{3.0, 2.0, 0.4});
  EXPECT_EQ(map.num_blocks(), 0u);
  EXPECT_EQ(map.memory_bytes(), 0u);
}

TEST(GlobalMapTest, ATileLandsAtItsRotatedPose) {
  GlobalMap map(kResM, 32);
  cv::Mat tile = Constant(21, 21, 0.0f);
  tile(cv::Rect(14, 8, 5, 5)).setTo(7.0f);  // a patch centred on pixel (16, 10)
  ImageGrid grid = TileGrid(21, 21);
  grid.x0_m = -0.5;  // pixel (10, 10) at the tile frame's origin
  grid.y0_m = 0.5;
  // Patch centre in the tile frame: x = -0.5 + 16 * 0.05 = 0.3, y = 0.5 - 10 * 0.05 = 0.
  const Pose2 T_world_tile{2.0, 1.0, M_PI / 2};
  map.AddTile(tile, grid, T_world_tile);
  const Point2 p = T_world_tile * Point2{0.3, 0.0};  // (2.0, 1.3)
  EXPECT_NEAR(At(map, p.x_m, p.y_m).value, 7.0f, 1e-4);
  // Where the patch would be without the rotation: unobserved.
  EXPECT_FALSE(At(map, 2.3, 1.0).observed);
}

TEST(GlobalMapTest, TilesFarApartAllocateOnlyTheirBlocks) {
  GlobalMap map(kResM, 32);  // a block is 1.6 m
  map.AddTile(Constant(10, 10, 1.0f), TileGrid(10, 10), Pose2{0.1, -0.1, 0.0});
  const std::size_t one = map.num_blocks();
  map.AddTile(Constant(10, 10, 1.0f), TileGrid(10, 10), Pose2{100.1, -0.1, 0.0});
  EXPECT_EQ(map.num_blocks(), 2 * one);
  EXPECT_EQ(map.memory_bytes(), map.num_blocks() * 2u * 32u * 32u * sizeof(float));
}

}  // namespace
}  // namespace uwbsar
