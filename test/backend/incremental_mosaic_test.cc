// IncrementalMosaic: after any sequence of updates the map equals a full render of the tiles
// it was last given, and an update reads back and redraws only what appeared, left or moved.
#include "backend/incremental_mosaic.h"

#include <gtest/gtest.h>

#include <cmath>
#include <map>
#include <opencv2/core.hpp>

namespace uwbsar {
namespace {

constexpr double kResM = 0.02;
constexpr int kBlockPx = 32;  // small blocks: a tile reaches many of them

/// Keyframe tiles 1 m apart: 1.2 m x 0.8 m of smooth positive texture with an unobserved (0)
/// corner.
struct Tiles {
  std::map<int, cv::Mat> images;
  std::map<int, int> loads;  ///< times each tile was read back
  ImageGrid grid;

  Tiles() {
    grid.resolution_m = kResM;
    grid.cols = 60;
    grid.rows = 40;
    grid.x0_m = -0.6;
    grid.y0_m = 0.4;
  }
  MosaicTile Make(int id, const Pose2& T_world_tile) {
    if (!images.count(id)) {
      cv::Mat image(grid.rows, grid.cols, CV_32FC1);
      cv::RNG rng(static_cast<std::uint64_t>(id) + 1);
      rng.fill(image, cv::RNG::UNIFORM, 0.5, 2.0);
      image(cv::Rect(0, 0, 10, 8)).setTo(0.0f);
      images[id] = image;
    }
    return {id, T_world_tile, grid, [this, id] {
              ++loads[id];
              return images.at(id);
            }};
  }
};

/// Largest difference between two renders (and whether they cover the same pixels).
double MaxDifference(const GlobalMap& a, const GlobalMap& b) {
  ImageGrid ga, gb;
  cv::Mat oa, ob;
  const cv::Mat ia = a.Render(&ga, &oa), ib = b.Render(&gb, &ob);
  EXPECT_EQ(ga.cols, gb.cols);
  EXPECT_EQ(ga.rows, gb.rows);
  EXPECT_DOUBLE_EQ(ga.x0_m, gb.x0_m);
  EXPECT_DOUBLE_EQ(ga.y0_m, gb.y0_m);
  if (ia.size() != ib.size()) return 1e9;
  EXPECT_EQ(cv::countNonZero(oa != ob), 0);
  return cv::norm(ia, ib, cv::NORM_INF);
}

GlobalMap FullRender(const std::vector<MosaicTile>& tiles) {
  GlobalMap full(kResM, kBlockPx);
  for (const MosaicTile& t : tiles) full.AddTile(t.load(), t.grid, t.T_world_tile);
  return full;
}

std::vector<MosaicTile> Corridor(Tiles* source, int n) {
  std::vector<MosaicTile> tiles;
  for (int i = 0; i < n; ++i) tiles.push_back(source->Make(i, {1.0 * i, 0.05 * i, 0.02 * i}));
  return tiles;
}

TEST(IncrementalMosaicTest, FirstUpdateEqualsAFullRender) {
  Tiles source;
  const std::vector<MosaicTile> tiles = Corridor(&source, 8);
  IncrementalMosaic mosaic(kResM, 0.5, kBlockPx);
  const MosaicUpdate u = mosaic.Update(tiles);
  EXPECT_EQ(u.added, 8u);
  EXPECT_EQ(u.tiles_drawn, 8u);
  EXPECT_EQ(u.blocks_redone, 0u);
  EXPECT_LT(MaxDifference(mosaic.map(), FullRender(tiles)), 1e-5);
}

TEST(IncrementalMosaicTest, RedrawsOnlyWhatAppearedLeftOrMoved) {
  Tiles source;
  std::vector<MosaicTile> tiles = Corridor(&source, 12);
  IncrementalMosaic mosaic(kResM, 0.5, kBlockPx);
  mosaic.Update(tiles);
  const std::size_t blocks = mosaic.map().num_blocks();
  source.loads.clear();

  tiles[3].T_world_tile.x_m += 0.15;                   // moved by a loop
  tiles.erase(tiles.begin() + 8);                      // retired
  tiles.push_back(source.Make(20, {12.5, 0.5, 0.2}));  // new, past the end
  const MosaicUpdate u = mosaic.Update(tiles);
  EXPECT_EQ(u.added, 1u);
  EXPECT_EQ(u.removed, 1u);
  EXPECT_EQ(u.moved, 1u);
  EXPECT_GT(u.blocks_redone, 0u);
  EXPECT_LT(u.blocks_redone, blocks / 2);
  EXPECT_LT(u.tiles_drawn, tiles.size() / 2 + 1);
  EXPECT_EQ(source.loads[0], 0);  // far from every change: never read back
  EXPECT_EQ(source.loads[11], 0);
  EXPECT_LT(MaxDifference(mosaic.map(), FullRender(tiles)), 1e-4);
}

TEST(IncrementalMosaicTest, AShiftUnderTheToleranceRedrawsNothing) {
  Tiles source;
  std::vector<MosaicTile> tiles = Corridor(&source, 6);
  IncrementalMosaic mosaic(kResM, 0.5, kBlockPx);
  mosaic.Update(tiles);
  source.loads.clear();
  for (MosaicTile& t : tiles) t.T_world_tile.x_m += 0.3 * kResM;  // 0.3 px
  MosaicUpdate u = mosaic.Update(tiles);
  EXPECT_EQ(u.moved, 0u);
  EXPECT_EQ(u.tiles_drawn, 0u);
  EXPECT_TRUE(source.loads.empty());
  // Shifts add up against the pose it was drawn at: the next 0.3 px passes the tolerance.
  for (MosaicTile& t : tiles) t.T_world_tile.x_m += 0.3 * kResM;
  u = mosaic.Update(tiles);
  EXPECT_EQ(u.moved, 6u);
  EXPECT_LT(MaxDifference(mosaic.map(), FullRender(tiles)), 1e-4);
}

TEST(IncrementalMosaicTest, EmptyingTheMapLeavesNoBlock) {
  Tiles source;
  IncrementalMosaic mosaic(kResM, 0.5, kBlockPx);
  mosaic.Update(Corridor(&source, 4));
  const MosaicUpdate u = mosaic.Update({});
  EXPECT_EQ(u.removed, 4u);
  EXPECT_EQ(mosaic.map().num_blocks(), 0u);
}

}  // namespace
}  // namespace uwbsar
