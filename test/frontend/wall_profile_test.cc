// Wall profiles (frontend/wall_profile.h): two tiles of one corridor, the second one's anchor
// moved sideways, give back that sideways offset to a fraction of a centimetre whatever the
// heading; tiles without a common wall, or a shift outside the searched range, are refused.
#include "frontend/wall_profile.h"

#include <gtest/gtest.h>

#include <cmath>

#include "test/frontend/corridor_tile.h"

namespace uwbsar {
namespace {

using testing::CorridorTile;
using testing::SpeckledWalls;
using testing::TileGrid;
constexpr double kPi = 3.14159265358979323846;

TEST(WallProfileTest, SidewaysOffsetOfTheSecondAnchorIsMeasuredAtAnyHeading) {
  const WallProfileConfig config;
  const ImageGrid grid = TileGrid();
  for (const double heading_deg : {0.0, 30.0, 90.0, -135.0}) {
    SCOPED_TRACE(heading_deg);
    const double h = heading_deg * kPi / 180;
    for (const double offset_m : {-0.083, 0.0, 0.037}) {
      // Walls 1.0 m left and 1.25 m right of a's anchor; b's anchor is offset_m further left.
      const WallProfile a =
          ComputeWallProfile(CorridorTile(grid, h, {1.0, -1.25}, 1), grid, h, config);
      const WallProfile b = ComputeWallProfile(
          CorridorTile(grid, h, {1.0 - offset_m, -1.25 - offset_m}, 2), grid, h, config);
      // The odometry predicts it 6 cm wrong.
      const WallProfileAlignment aligned = AlignWallProfiles(a, b, offset_m + 0.06, config);
      EXPECT_TRUE(aligned.accepted) << aligned.reason;
      EXPECT_NEAR(aligned.offset_m, offset_m, 0.004);
      EXPECT_GT(aligned.correlation, 0.8);
    }
  }
}

TEST(WallProfileTest, TilesWithoutACommonWallAreRefused) {
  const WallProfileConfig config;
  const ImageGrid grid = TileGrid();
  const WallProfile a = ComputeWallProfile(CorridorTile(grid, 0.0, {1.0}, 1), grid, 0.0, config);
  const WallProfile b = ComputeWallProfile(CorridorTile(grid, 0.0, {-1.6}, 2), grid, 0.0, config);
  const WallProfileAlignment aligned = AlignWallProfiles(a, b, 0.0, config);
  EXPECT_FALSE(aligned.accepted);
  EXPECT_FALSE(aligned.reason.empty());
  // Noise alone: no wall at all.
  const WallProfile empty = ComputeWallProfile(CorridorTile(grid, 0.0, {}, 3), grid, 0.0, config);
  EXPECT_FALSE(AlignWallProfiles(empty, b, 0.0, config).accepted);
}

TEST(WallProfileTest, AShiftBeyondTheSearchedRangeIsRefusedNotClamped) {
  WallProfileConfig config;
  const ImageGrid grid = TileGrid();
  const WallProfile a =
      ComputeWallProfile(CorridorTile(grid, 0.0, {1.0, -1.25}, 1), grid, 0.0, config);
  const WallProfile b =
      ComputeWallProfile(CorridorTile(grid, 0.0, {0.7, -1.55}, 2), grid, 0.0, config);
  // The true offset is 0.30 m; the odometry says 0.05 m and the search reaches +-0.15 m.
  const WallProfileAlignment aligned = AlignWallProfiles(a, b, 0.05, config);
  EXPECT_FALSE(aligned.accepted);
  EXPECT_FALSE(aligned.reason.empty());
  config.search_m = 0.4;
  const WallProfileAlignment wide = AlignWallProfiles(a, b, 0.05, config);
  EXPECT_TRUE(wide.accepted) << wide.reason;
  EXPECT_NEAR(wide.offset_m, 0.30, 0.004);
}

// As on floor50's tour, seed 5: two keyframes 5 m apart each see the right-hand wall behind a
// cabinet, but not the same cabinet (one 0.74 m from the path, the other 0.62 m). The whole
// profile's best shift follows the cabinets, 12 cm off; the left wall alone and the right walls
// alone disagree by as much, so the edge is refused.
TEST(WallProfileTest, SidesThatDisagreeAreRefused) {
  WallProfileConfig config;
  const ImageGrid grid = TileGrid();
  auto tile = [&](double cabinet_m, unsigned seed) {
    SpeckledWalls walls(grid, seed);
    walls.Add(1, 0, 1.0, -1.0, 1.0);                                    // left wall
    walls.Add(1, 0, -1.0, -1.0, 1.0);                                   // right wall
    for (int k = 0; k < 6; ++k) walls.Add(1, 0, cabinet_m, -0.5, 0.5);  // a strong cabinet
    return ComputeWallProfile(walls.tile(), grid, 0.0, config);
  };
  const WallProfile a = tile(-0.74, 1), b = tile(-0.62, 2);  // same anchor: true offset 0
  const WallProfileAlignment refused = AlignWallProfiles(a, b, 0.0, config);
  EXPECT_FALSE(refused.accepted);
  EXPECT_NE(refused.reason.find("disagree"), std::string::npos) << refused.reason;
  EXPECT_GT(refused.side_disagreement_m, config.max_side_disagreement_m);
  config.max_side_disagreement_m = 0.0;  // not checked: the compromise is taken, cm off
  const WallProfileAlignment unchecked = AlignWallProfiles(a, b, 0.0, config);
  ASSERT_TRUE(unchecked.accepted) << unchecked.reason;
  EXPECT_GT(std::abs(unchecked.offset_m), 0.03);
  // The same cabinet in both: the sides agree and the offset is found.
  config = WallProfileConfig{};
  const WallProfileAlignment same = AlignWallProfiles(a, tile(-0.74, 3), 0.0, config);
  EXPECT_TRUE(same.accepted) << same.reason;
  EXPECT_LT(same.side_disagreement_m, 0.01);
  EXPECT_NEAR(same.offset_m, 0.0, 0.004);
  // A wall on one side only: nothing to compare, the edge stands on that side.
  const WallProfile left_a =
      ComputeWallProfile(CorridorTile(grid, 0.0, {1.0}, 4), grid, 0.0, config);
  const WallProfile left_b =
      ComputeWallProfile(CorridorTile(grid, 0.0, {0.96}, 5), grid, 0.0, config);
  const WallProfileAlignment one_side = AlignWallProfiles(left_a, left_b, 0.0, config);
  EXPECT_TRUE(one_side.accepted) << one_side.reason;
  EXPECT_EQ(one_side.side_disagreement_m, 0.0);
  EXPECT_NEAR(one_side.offset_m, 0.04, 0.004);
}

TEST(WallProfileTest, WrongInputIsAnError) {
  const WallProfileConfig config;
  const ImageGrid grid = TileGrid();
  EXPECT_THROW(ComputeWallProfile(cv::Mat(3, 3, CV_32FC1, 0.0f), grid, 0.0, config),
               std::invalid_argument);
  EXPECT_THROW(ComputeWallProfile(cv::Mat(grid.rows, grid.cols, CV_8UC1), grid, 0.0, config),
               std::invalid_argument);
  WallProfileConfig coarse = config;
  coarse.bin_m = 0.01;
  const cv::Mat tile = CorridorTile(grid, 0.0, {1.0}, 1);
  EXPECT_THROW(AlignWallProfiles(ComputeWallProfile(tile, grid, 0.0, config),
                                 ComputeWallProfile(tile, grid, 0.0, coarse), 0.0, config),
               std::invalid_argument);
}

}  // namespace
}  // namespace uwbsar
