#include "eval/compare/grid_alignment.h"

#include <gtest/gtest.h>

#include <cmath>

#include "eval/compare/map_metrics.h"
#include "test/shared_data.h"
#include "test_maps.h"

namespace uwbsar {
namespace {

constexpr double kDeg = M_PI / 180.0;
const Pose2 kMoved{0.4, -0.25, 7.0 * kDeg};  // the acceptance case

/// Checks that T is `expected` within one cell (0.05 m) and 0.5 deg.
void ExpectWithinOneCell(const Pose2& T, const Pose2& expected) {
  EXPECT_LT(std::hypot(T.x_m - expected.x_m, T.y_m - expected.y_m), 0.05)
      << "T = (" << T.x_m << ", " << T.y_m << "), expected (" << expected.x_m << ", "
      << expected.y_m << ")";
  EXPECT_LT(std::abs(NormalizeAngle(T.yaw_rad - expected.yaw_rad)), 0.5 * kDeg)
      << "yaw " << T.yaw_rad / kDeg << " deg, expected " << expected.yaw_rad / kDeg;
}

TEST(GridAlignmentTest, IdenticalGridsAlignToIdentity) {
  UWBSAR_NEED_SEED_LAB_MAP();
  const OccupancyGrid lidar = testing::SeedLabGrid();
  const std::vector<Point2> points = OccupiedCellCenters(lidar);
  const AlignmentResult a = AlignPointSets(points, points, Pose2{}, CompareConfig{});
  ASSERT_TRUE(a.accepted) << a.reason;
  EXPECT_LT(std::hypot(a.T_target_source.x_m, a.T_target_source.y_m), 1e-4);
  EXPECT_LT(std::abs(a.T_target_source.yaw_rad), 1e-4);
  EXPECT_DOUBLE_EQ(a.inlier_fraction, 1.0);
  EXPECT_LT(a.inlier_rmse_m, 1e-4);
}

class MovedCopyTest : public ::testing::TestWithParam<std::string> {};

TEST_P(MovedCopyTest, RealignsShiftedRotatedRasterisedCopyAndScoresItIdentical) {
  const OccupancyGrid lidar = testing::SeedLabGrid();
  const OccupancyGrid copy = testing::RasterizedCopy(lidar, kMoved);
  CompareConfig config;
  config.icp_method = GetParam();
  const AlignmentResult a =
      AlignPointSets(OccupiedCellCenters(copy), OccupiedCellCenters(lidar), Pose2{}, config);
  ASSERT_TRUE(a.accepted) << a.reason;
  ExpectWithinOneCell(a.T_target_source, kMoved.Inverse());  // T_lidar_copy
  EXPECT_GT(a.inlier_fraction, 0.95);

  const MapMetrics m = CompareOnLidarGrid(copy, lidar, a.T_target_source, 1).metrics;
  EXPECT_GT(m.evaluated_cells, 10000);
  EXPECT_GT(m.precision, 0.99);
  EXPECT_GT(m.recall, 0.99);
  EXPECT_GT(m.f1, 0.99);
  EXPECT_LT(m.sar_to_lidar.p95_m, 0.05 + 1e-6);
  EXPECT_LT(m.lidar_to_sar.p95_m, 0.05 + 1e-6);
  // Without alignment the same copy is a bad match: the score separates the two.
  const MapMetrics raw = CompareOnLidarGrid(copy, lidar, Pose2{}, 1).metrics;
  EXPECT_LT(raw.f1, 0.5);
}

INSTANTIATE_TEST_SUITE_P(Methods, MovedCopyTest,
                         ::testing::Values("point_to_point", "point_to_plane"));

TEST(GridAlignmentTest, PointToPlaneRealignsExactCopyExactly) {
  UWBSAR_NEED_SEED_LAB_MAP();
  // The same cells, declared with a moved and rotated origin: an exact rigid copy. (Point-to-
  // point ICP can lock up to a cell off here: cell centres along a wall alias each other.)
  const OccupancyGrid lidar = testing::SeedLabGrid();
  OccupancyGrid copy = lidar;
  copy.origin = kMoved * lidar.origin;
  CompareConfig config;
  config.icp_method = "point_to_plane";
  const AlignmentResult a =
      AlignPointSets(OccupiedCellCenters(copy), OccupiedCellCenters(lidar), Pose2{}, config);
  ASSERT_TRUE(a.accepted) << a.reason;
  ExpectWithinOneCell(a.T_target_source, kMoved.Inverse());
  EXPECT_LT(a.inlier_rmse_m, 1e-3);
  const MapMetrics m = CompareOnLidarGrid(copy, lidar, a.T_target_source, 1).metrics;
  EXPECT_GT(m.f1, 0.99);
  EXPECT_EQ(m.differing_cells, 0);
  EXPECT_LT(m.sar_to_lidar.max_m, 1e-3);  // exact copy: residual of the ICP only
}

TEST(GridAlignmentTest, UserInitialTransformIsWhereIcpStarts) {
  UWBSAR_NEED_SEED_LAB_MAP();
  // 40 deg is beyond ICP's reach from the origins but fine from a close user guess.
  const OccupancyGrid lidar = testing::SeedLabGrid();
  const Pose2 far{0.3, 0.2, 40.0 * kDeg};
  const OccupancyGrid copy = testing::RasterizedCopy(lidar, far);
  const auto source = OccupiedCellCenters(copy);
  const auto target = OccupiedCellCenters(lidar);
  const Pose2 guess = far.Inverse() * Pose2{0.1, -0.1, 3.0 * kDeg};
  const AlignmentResult a = AlignPointSets(source, target, guess, {});
  ASSERT_TRUE(a.accepted) << a.reason;
  ExpectWithinOneCell(a.T_target_source, far.Inverse());
  EXPECT_DOUBLE_EQ(a.T_initial.yaw_rad, guess.yaw_rad);
}

TEST(GridAlignmentTest, TooFewPointsAreReportedNotAligned) {
  const std::vector<Point2> two = {{0, 0}, {1, 0}};
  const AlignmentResult a = AlignPointSets(two, two, Pose2{0.1, 0, 0}, {});
  EXPECT_FALSE(a.accepted);
  EXPECT_NE(a.reason.find("too few"), std::string::npos) << a.reason;
  EXPECT_DOUBLE_EQ(a.T_target_source.x_m, 0.1);  // initial transform kept
}

TEST(GridAlignmentTest, DistantPointSetsAreRejected) {
  UWBSAR_NEED_SEED_LAB_MAP();
  const OccupancyGrid lidar = testing::SeedLabGrid();
  const auto target = OccupiedCellCenters(lidar);
  std::vector<Point2> source = target;
  for (Point2& p : source) p.x_m += 100.0;
  const AlignmentResult a = AlignPointSets(source, target, Pose2{}, {});
  EXPECT_FALSE(a.accepted);
  EXPECT_FALSE(a.reason.empty());
  EXPECT_DOUBLE_EQ(a.T_target_source.x_m, 0.0);
}

}  // namespace
}  // namespace uwbsar
