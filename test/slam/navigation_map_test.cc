// KeyframeWallRidges: on a straight keyframe each radar gets the near face of the first wall on
// its side (the corridor tile of the wall-profile tests, test/frontend/corridor_tile.h); a
// turning keyframe and a side without a wall get none.
#include "slam/outputs/navigation_map.h"

#include <gtest/gtest.h>

#include "test/frontend/corridor_tile.h"

namespace uwbsar {
namespace {

std::vector<SensorGeometry> Radars() {
  SensorGeometry left;
  left.T_robot_sensor = {0.0, 0.18, M_PI / 2};
  left.min_range_m = 0.4;
  left.max_range_m = 2.0;
  SensorGeometry right = left;
  right.T_robot_sensor = {0.0, -0.18, -M_PI / 2};
  return {left, right};
}

struct Corridor {
  ImageGrid grid = testing::TileGrid();
  cv::Mat tile;
  NavigationKeyframe Keyframe(double turn_rad) const {
    NavigationKeyframe k;
    k.detected = &tile;
    k.grid = grid;
    for (double t = 0.0; t <= 1.0; t += 0.01)
      k.T_anchor_robot.push_back({t - 0.5, 0.0, t * turn_rad});
    return k;
  }
};

TEST(NavigationMapTest, AStraightKeyframeGivesEachRadarItsFirstWall) {
  Corridor c;
  c.tile = testing::CorridorTile(c.grid, 0.0, {1.2, 1.9, -0.9}, 3);
  const std::vector<WallRidge> ridges = slam::KeyframeWallRidges(c.Keyframe(0.0), Radars(), {});
  ASSERT_EQ(ridges.size(), 2u);
  ASSERT_TRUE(ridges[0].found);
  ASSERT_TRUE(ridges[1].found);
  EXPECT_NEAR(ridges[0].normal_y, 1.0, 1e-9);
  // The near face: within the wall's speckled thickness (1.5 cm sigma) before its centre.
  EXPECT_NEAR(ridges[0].offset_m, 1.2, 0.05);
  EXPECT_LE(ridges[0].offset_m, 1.2);
  EXPECT_NEAR(ridges[1].offset_m, -0.9, 0.05);
  EXPECT_GE(ridges[1].offset_m, -0.9);
}

TEST(NavigationMapTest, NoRidgeWhereTheRobotTurnedOrNoWallStands) {
  Corridor c;
  c.tile = testing::CorridorTile(c.grid, 0.0, {1.2}, 3);
  const std::vector<WallRidge> straight = slam::KeyframeWallRidges(c.Keyframe(0.0), Radars(), {});
  EXPECT_TRUE(straight[0].found);
  EXPECT_FALSE(straight[1].found);  // nothing on the right
  const std::vector<WallRidge> turning =
      slam::KeyframeWallRidges(c.Keyframe(0.5), Radars(), {});  // 29 deg within the tile
  EXPECT_FALSE(turning[0].found);
  EXPECT_FALSE(turning[1].found);
}

}  // namespace
}  // namespace uwbsar
