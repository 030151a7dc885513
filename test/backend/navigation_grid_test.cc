// BuildNavigationGrid: the inverse sensor model of a side-looking radar on a synthetic tile (a
// wall 1.5 m left of a straight 2 m path, a second wall behind it): free before the first
// return, occupied at it, shadow behind; dashed walls closed by the line width and the ridge;
// doorways kept open; the swept footprint free; keyframes fused in log-odds.
#include "backend/navigation_grid.h"

#include <gtest/gtest.h>

#include <vector>

#include "core/errors.h"
#include "test/navigation_checks.h"

namespace uwbsar {
namespace {

constexpr double kCellM = 0.05;

/// A tile on x in [-0.5, 2.5], y in [-3.5, 3.5] at 1 cm, imaged everywhere at a faint floor.
struct Scene {
  ImageGrid grid = ImageGrid::Covering(-0.5, 2.5, -3.5, 3.5, 0.01);
  cv::Mat tile = cv::Mat(grid.rows, grid.cols, CV_32FC1, cv::Scalar(0.01f));

  /// A wall along y = y_m over x in [x0, x1] at `value`, 3 px thick.
  void Wall(double y_m, double x0, double x1, float value) {
    const int row = static_cast<int>(std::lround(grid.YToRow(y_m)));
    for (int c = static_cast<int>(std::lround(grid.XToCol(x0)));
         c <= static_cast<int>(std::lround(grid.XToCol(x1))); ++c) {
      for (int r = row - 1; r <= row + 1; ++r) tile.at<float>(r, c) = value;
    }
  }
  /// Gaps of `gap_m` every 0.1 m in the wall at y_m, at `value`.
  void Dashes(double y_m, double gap_m, float value) {
    for (double x = 0.0; x < 2.0; x += 0.1) Wall(y_m, x, x + gap_m, value);
  }
  NavigationKeyframe Keyframe() const {
    NavigationKeyframe k;
    k.detected = &tile;
    k.grid = grid;
    for (double x = 0.0; x <= 2.0; x += 0.005) k.T_anchor_robot.push_back({x, 0.0, 0.0});
    return k;
  }
};

std::vector<SensorGeometry> Radars() {
  SensorGeometry left;
  left.T_robot_sensor = {0.0, 0.18, M_PI / 2};
  left.min_range_m = 0.4;
  left.max_range_m = 3.0;
  SensorGeometry right = left;
  right.T_robot_sensor = {0.0, -0.18, -M_PI / 2};
  return {left, right};
}

OccupancyGrid Build(const std::vector<NavigationKeyframe>& keyframes,
                    const NavigationGridConfig& config = {}, std::vector<Pose2> path = {}) {
  return BuildNavigationGrid(keyframes, path, Radars(), config, kCellM, 1.0f, 1e8);
}

std::int8_t At(const OccupancyGrid& g, double x, double y) {
  int r = 0, c = 0;
  if (!g.CellOf({x, y}, &r, &c)) return OccupancyGrid::kUnknown;
  return g.At(r, c);
}

TEST(NavigationGridTest, FreeBeforeTheFirstReturnOccupiedAtItShadowBehind) {
  Scene s;
  s.Wall(1.5, -0.5, 2.5, 1.0f);
  s.Wall(2.5, -0.5, 2.5, 1.0f);
  const OccupancyGrid g = Build({s.Keyframe()});
  EXPECT_EQ(At(g, 1.0, 0.4), OccupancyGrid::kFree);  // the blind zone: the pulse crossed it
  EXPECT_EQ(At(g, 1.0, 1.2), OccupancyGrid::kFree);
  EXPECT_EQ(At(g, 1.0, 1.52), OccupancyGrid::kOccupied);
  EXPECT_EQ(At(g, 1.0, 2.0), OccupancyGrid::kUnknown);   // shadow
  EXPECT_EQ(At(g, 1.0, 2.52), OccupancyGrid::kUnknown);  // the wall behind is never reached
  // No return on the right: nothing is freed there (free_without_return: false) ...
  EXPECT_EQ(At(g, 1.0, -1.0), OccupancyGrid::kUnknown);
  // ... unless asked.
  NavigationGridConfig config;
  config.free_without_return = true;
  EXPECT_EQ(At(Build({s.Keyframe()}, config), 1.0, -1.0), OccupancyGrid::kFree);
}

TEST(NavigationGridTest, ADashedWallStopsEveryLineThatMeetsIt) {
  Scene s;
  s.Dashes(1.5, 0.07, 1.0f);  // 7 cm of wall, 3 cm gap, with nothing in the gaps
  s.Wall(2.5, -0.5, 2.5, 1.0f);
  NavigationGridConfig narrow;
  narrow.ray_width_m = 0.0;
  // A 1-px line slips through the gaps, hits the wall behind and frees the room between.
  int leaked = 0, leaked_wide = 0;
  const OccupancyGrid thin = Build({s.Keyframe()}, narrow);
  const OccupancyGrid wide = Build({s.Keyframe()});
  for (double x = 0.2; x < 1.8; x += kCellM) {
    leaked += At(thin, x, 2.0) == OccupancyGrid::kFree;
    leaked_wide += At(wide, x, 2.0) == OccupancyGrid::kFree;
  }
  EXPECT_GT(leaked, 5);
  EXPECT_EQ(leaked_wide, 0);
}

TEST(NavigationGridTest, TheRidgeClosesAWeakStretchButNotADoorway) {
  Scene s;
  s.Wall(1.5, -0.5, 2.5, 1.0f);
  s.Wall(1.5, 0.4, 0.7, 0.1f);    // a weak stretch: under return_fraction, over support
  s.Wall(1.5, 1.2, 1.6, 0.005f);  // a doorway: nothing there
  s.Wall(2.5, -0.5, 2.5, 1.0f);
  NavigationKeyframe k = s.Keyframe();
  const OccupancyGrid open = Build({k});
  EXPECT_EQ(At(open, 0.55, 2.0), OccupancyGrid::kFree);  // seen through the weak stretch
  WallRidge ridge;
  ridge.found = true;
  ridge.normal_x = 0.0, ridge.normal_y = 1.0, ridge.offset_m = 1.49;
  k.ridges = {ridge, WallRidge{}};
  const OccupancyGrid closed = Build({k});
  EXPECT_EQ(At(closed, 0.55, 1.52), OccupancyGrid::kOccupied);
  EXPECT_EQ(At(closed, 0.55, 2.0), OccupancyGrid::kUnknown);
  EXPECT_EQ(At(closed, 1.4, 1.52), OccupancyGrid::kFree);  // the doorway stays open
  EXPECT_EQ(At(closed, 1.4, 2.0), OccupancyGrid::kFree);
}

TEST(NavigationGridTest, KeyframesVoteInLogOdds) {
  Scene clutter, clear;
  clutter.Wall(0.8, 0.9, 1.1, 1.0f);  // a return that one keyframe saw
  clutter.Wall(1.5, -0.5, 2.5, 1.0f);
  clear.Wall(1.5, -0.5, 2.5, 1.0f);
  EXPECT_EQ(At(Build({clutter.Keyframe()}), 1.0, 0.8), OccupancyGrid::kOccupied);
  // Seen free by three others: 0.85 - 3 x 0.4 = -0.35, free.
  const OccupancyGrid g =
      Build({clutter.Keyframe(), clear.Keyframe(), clear.Keyframe(), clear.Keyframe()});
  EXPECT_EQ(At(g, 1.0, 0.8), OccupancyGrid::kFree);
}

TEST(NavigationGridTest, TheSweptFootprintIsFreeWhateverTheRadarSaw) {
  const OccupancyGrid alone = Build({}, {}, {{0.0, 0.0, 0.0}, {0.01, 0.0, 0.0}});
  EXPECT_EQ(At(alone, 0.0, 0.1), OccupancyGrid::kFree);
  EXPECT_EQ(At(alone, 0.0, 0.3), OccupancyGrid::kUnknown);
  // On the map's lattice (multiples of the cell), so grids of one map line up.
  EXPECT_NEAR(alone.origin.x_m / kCellM, std::round(alone.origin.x_m / kCellM), 1e-9);
  Scene s;
  s.Wall(0.7, -0.5, 2.5, 1.0f);
  NavigationGridConfig wide;
  wide.footprint_radius_m = 0.8;
  EXPECT_EQ(At(Build({s.Keyframe()}), 1.0, 0.72), OccupancyGrid::kOccupied);
  EXPECT_EQ(At(Build({s.Keyframe()}, wide, {{1.0, 0.0, 0.0}}), 1.0, 0.72), OccupancyGrid::kFree);
}

TEST(NavigationGridTest, AWildPoseIsRefusedBeforeAllocation) {
  EXPECT_THROW(
      BuildNavigationGrid({}, {{0.0, 0.0, 0.0}, {1e6, 1e6, 0.0}}, Radars(), {}, kCellM, 1.0f, 1e8),
      InputError);
}

}  // namespace
}  // namespace uwbsar

namespace uwbsar {
namespace {

// The acceptance checks' planner (test/navigation_checks.h) keeps the robot's radius from
// occupied cells and never enters unknown ones; CrossesWall sees a segment through a wall.
TEST(NavigationChecksTest, PlannerKeepsTheRobotRadiusAndCrossingsAreSeen) {
  OccupancyGrid g;
  g.rows = 40, g.cols = 40, g.resolution_m = 0.05;
  g.cells.assign(1600, OccupancyGrid::kFree);
  auto set = [&](int r, int c, std::int8_t v) {
    g.cells[static_cast<std::size_t>(r) * 40 + c] = v;
  };
  for (int r = 0; r < 40; ++r) set(r, 20, OccupancyGrid::kOccupied);  // a wall x = 1.0 .. 1.05
  for (int r = 10; r < 17; ++r) set(r, 20, OccupancyGrid::kFree);     // a 0.35 m gap
  const Point2 a{0.5, 1.0}, b{1.5, 1.0};
  EXPECT_TRUE(testing::PlanPath(g, a, b, 0.2).empty());            // the robot (0.4 m) does not fit
  for (int r = 10; r < 22; ++r) set(r, 20, OccupancyGrid::kFree);  // 0.6 m
  const std::vector<Point2> path = testing::PlanPath(g, a, b, 0.2);
  ASSERT_FALSE(path.empty());
  EXPECT_FALSE(testing::CrossesWall(g, path));
  EXPECT_TRUE(testing::CrossesWall(g, {{0.5, 0.3}, {1.5, 0.3}}));
  for (int r = 10; r < 22; ++r) set(r, 20, OccupancyGrid::kUnknown);
  EXPECT_TRUE(testing::PlanPath(g, a, b, 0.2).empty());  // unknown is not entered
}

}  // namespace
}  // namespace uwbsar
