// WallEdgeFinder (slam/wall_edges.h): keyframes of one straight corridor get wall edges to
// the keyframes min_gap..max_gap before them, measuring their true sideways offsets; a turn in
// between, or a tile cut short, gives none; the edge keeps the odometry along the path.
#include "slam/wall_edges.h"

#include <gtest/gtest.h>

#include <Eigen/Eigenvalues>
#include <cmath>

#include "test/frontend/corridor_tile.h"

namespace uwbsar::slam {
namespace {

using testing::CorridorTile;
using testing::TileGrid;

constexpr double kPi = 3.14159265358979323846;

/// Keyframe `id` of a corridor whose walls run along the heading `heading_rad`, 1.0 m left and
/// 1.25 m right of the line through the origin; the robot is `along_m` along that line and
/// `across_m` left of it (anchors keep the world orientation).
Keyframe CorridorKeyframe(int id, double along_m, double across_m, double heading_rad,
                          bool complete, cv::Mat* detected) {
  const double c = std::cos(heading_rad), s = std::sin(heading_rad);
  const double x_m = along_m * c - across_m * s, y_m = along_m * s + across_m * c;
  Keyframe k;
  k.id = id;
  k.complete = complete;
  k.T_world_anchor = {x_m, y_m, 0.0};
  k.T_world_robot = {x_m, y_m, heading_rad};
  *detected = CorridorTile(TileGrid(), heading_rad, {1.0 - across_m, -1.25 - across_m},
                           static_cast<unsigned>(id + 1));
  return k;
}

TEST(WallEdgesTest, EdgeKeepsTheOdometryAlongThePathAndMeasuresAcrossIt) {
  // Path along anchor +y (heading 90 deg): across it is -x.
  const Pose2 odometry{0.05, 3.0, 0.01};
  const PoseGraphEdge e = WallEdgeFinder::MakeEdge(4, 7, odometry, kPi / 2, 0.02, 0.02);
  EXPECT_EQ(e.kind, EdgeKind::kWall);
  EXPECT_EQ(e.from_id, 4);
  EXPECT_EQ(e.to_id, 7);
  EXPECT_NEAR(e.T_from_to.x_m, -0.02, 1e-12);  // the measured offset along (-1, 0)
  EXPECT_NEAR(e.T_from_to.y_m, 3.0, 1e-12);    // the odometry along the path
  EXPECT_NEAR(e.T_from_to.yaw_rad, 0.01, 1e-12);
  Eigen::SelfAdjointEigenSolver<Eigen::Matrix2d> eig(e.information.topLeftCorner<2, 2>());
  EXPECT_NEAR(eig.eigenvalues()(1), 1.0 / (0.02 * 0.02), 1e-6);
  EXPECT_NEAR(std::abs(eig.eigenvectors().col(1).x()), 1.0, 1e-9);
  EXPECT_LT(eig.eigenvalues()(0), 1e-4 * eig.eigenvalues()(1));
  EXPECT_LT(e.information(2, 2), 1e-4 * eig.eigenvalues()(1));
}

TEST(WallEdgesTest, KeyframesOfOneCorridorAreTiedToTheOnesBeforeThem) {
  const WallProfileConfig config;  // gaps 2..6
  WallEdgeFinder finder(config);
  // Ten keyframes 1 m apart, the path wandering sideways by a few centimetres.
  const double y_m[10] = {0.0, 0.02, 0.05, 0.04, 0.01, -0.03, -0.02, 0.0, 0.03, 0.06};
  for (int id = 0; id < 10; ++id) {
    cv::Mat detected;
    // The odometry's anchors are straight (y = 0): it has not seen the wandering.
    Keyframe k = CorridorKeyframe(id, id * 1.0, y_m[id], 0.0, true, &detected);
    k.T_world_anchor.y_m = k.T_world_robot.y_m = 0.0;
    const std::vector<PoseGraphEdge> edges = finder.Add(k, detected, TileGrid());
    ASSERT_EQ(static_cast<int>(edges.size()), std::max(0, std::min(id, 6) - 1)) << id;
    for (const PoseGraphEdge& e : edges) {
      EXPECT_EQ(e.to_id, id);
      EXPECT_GE(id - e.from_id, 2);
      EXPECT_LE(id - e.from_id, 6);
      EXPECT_NEAR(e.T_from_to.y_m, y_m[id] - y_m[e.from_id], 0.004) << e.from_id << " -> " << id;
      EXPECT_NEAR(e.T_from_to.x_m, id - e.from_id, 1e-9);
    }
  }
  EXPECT_EQ(finder.pairs_tried(), 0 + 0 + 1 + 2 + 3 + 4 + 5 + 5 + 5 + 5);
}

TEST(WallEdgesTest, NoEdgeAcrossATurnOrFromATileCutShort) {
  const WallProfileConfig config;
  WallEdgeFinder finder(config);
  cv::Mat detected;
  for (int id = 0; id < 3; ++id) {
    finder.Add(CorridorKeyframe(id, id, 0.0, 0.0, true, &detected), detected, TileGrid());
  }
  // Keyframe 3 has turned 5 deg (max_heading_change_deg 3): not on the same straight stretch.
  const double turned = 5 * kPi / 180;
  EXPECT_TRUE(finder.Add(CorridorKeyframe(3, 3, 0.0, turned, true, &detected), detected, TileGrid())
                  .empty());
  // Keyframe 4 heads as 3 did, but 0..2 are behind the turn: only 3 is eligible, at gap 1.
  EXPECT_TRUE(finder.Add(CorridorKeyframe(4, 4, 0.0, turned, true, &detected), detected, TileGrid())
                  .empty());
  // A tile cut short is neither paired nor kept.
  EXPECT_TRUE(
      finder.Add(CorridorKeyframe(5, 5, 0.0, turned, false, &detected), detected, TileGrid())
          .empty());
  EXPECT_EQ(
      finder.Add(CorridorKeyframe(6, 6, 0.0, turned, true, &detected), detected, TileGrid()).size(),
      2u);  // 3 and 4
  WallProfileConfig off = config;
  off.enabled = false;
  WallEdgeFinder disabled(off);
  for (int id = 0; id < 5; ++id) {
    EXPECT_TRUE(
        disabled.Add(CorridorKeyframe(id, id, 0.0, 0.0, true, &detected), detected, TileGrid())
            .empty());
  }
}

}  // namespace
}  // namespace uwbsar::slam
