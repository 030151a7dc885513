// Wall edges (EdgeKind::kWall, backend/pose_graph.h): the sideways offset between keyframes a
// few metres apart on one straight stretch (frontend/wall_profile.h). On a straight corridor
// no loop observes the odometry's heading drift; wall edges straighten the bow it puts into the
// path. They do not free the trajectory's calibration block on their own (they never see the
// turns' scale, which only a loop ties to the drift); once an accepted loop has freed it, they
// measure the drift. A wrong one is rejected by its chi2, and none is ever held back for
// support or counted as a loop.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <random>

#include "backend/odometry_calibration.h"
#include "backend/pose_graph.h"
#include "test/backend/calibration_routes.h"

namespace uwbsar {
namespace {

using testing::BuildOdometryChain;
using testing::DriveSteps;
using testing::GraphAte;
using testing::OdometryRun;

constexpr double kDriftRadPerM = 0.003;  // the simulator's: wheel_scale_asymmetry / wheelbase
constexpr double kLateralStdM = 0.02;    // place_recognition.wall_profiles.lateral_std_m

/// 40 m of straight corridor in 1 m steps (keyframes), driven with a heading drift.
OdometryRun Corridor() {
  return DriveSteps({0.0, kDriftRadPerM, 0.0}, std::vector<Pose2>(40, {1.0, 0.0, 0.0}));
}

/// Wall edges k - gap -> k (gap 2..6) in the robot frames of the nodes: the odometry's step
/// along the path and in yaw, the true sideways offset with 1 cm of noise (fixed seed) across
/// it; with `wrong_at` >= 0 the edges into that node 20 cm off.
std::vector<int> AddWallEdges(const OdometryRun& run, int wrong_at, PoseGraph* g) {
  std::mt19937 rng(7);
  std::normal_distribution<double> noise(0.0, 0.01);
  Eigen::Matrix3d information = Eigen::Matrix3d::Zero();
  information(1, 1) = 1.0 / (kLateralStdM * kLateralStdM);
  information(0, 0) = information(2, 2) = 1e-5 * information(1, 1);
  std::vector<int> indices;
  for (int k = 2; k < static_cast<int>(run.truth.size()); ++k) {
    for (int gap = 2; gap <= std::min(6, k); ++gap) {
      Pose2 odometry;
      for (int s = k - gap; s < k; ++s) odometry = odometry * run.measured[s];
      const Pose2 truth = Between(run.truth[k - gap], run.truth[k]);
      PoseGraphEdge e;
      e.from_id = k - gap;
      e.to_id = k;
      e.T_from_to = {odometry.x_m, truth.y_m + noise(rng) + (k == wrong_at ? 0.2 : 0.0),
                     odometry.yaw_rad};
      e.information = information;
      e.kind = EdgeKind::kWall;
      indices.push_back(g->AddEdge(e));
    }
  }
  return indices;
}

TEST(WallEdgeTest, StraightCorridorIsStraightenedWithoutLoopsAndTheCalibrationStaysAtThePrior) {
  const OdometryRun run = Corridor();
  PoseGraph odometry_only;  // default backend: min_loop_support 1, calibration on
  BuildOdometryChain(run, &odometry_only);
  odometry_only.Optimize();
  PoseGraph g;
  BuildOdometryChain(run, &g);
  AddWallEdges(run, -1, &g);
  const OptimizeResult r = g.Optimize();
  EXPECT_TRUE(r.converged) << r.termination;
  EXPECT_EQ(r.num_loops, 0);        // wall edges are not loops
  EXPECT_TRUE(r.rejected.empty());  // and are not held back as unsupported
  const OdometryCalibration c = g.OdometryCalibrations().at(0);
  const double ate_odometry = GraphAte(odometry_only, run.truth), ate = GraphAte(g, run.truth);
  std::printf("drift estimate %.5f rad/m (truth %.5f); ATE %.2f cm, odometry alone %.2f cm\n",
              c[kCalibHeadingDrift], kDriftRadPerM, ate * 100, ate_odometry * 100);
  EXPECT_EQ(odometry_only.OdometryCalibrations().at(0)[kCalibHeadingDrift], 0.0);
  EXPECT_EQ(c, (OdometryCalibration{0.0, 0.0, 0.0}));  // no loop: the block stays at its prior
  EXPECT_GT(ate_odometry, 0.1);  // 2.4 m off at the end, 19 cm after the ATE alignment
  EXPECT_LT(ate, ate_odometry / 5);
}

// One accepted loop (the last two metres driven again) frees the block; the wall edges along
// the whole corridor then measure the drift (a wheel-only base's: a gyro's heading error is its
// bias over time, gyro_bias_track_test.cc).
TEST(WallEdgeTest, OnceALoopFreesTheCalibrationTheWallEdgesMeasureTheDrift) {
  const OdometryRun run = Corridor();
  BackendConfig config;
  config.odometry_model = OdometryModel::kWheel;
  PoseGraph g(config);
  BuildOdometryChain(run, &g);
  AddWallEdges(run, -1, &g);
  const int last = static_cast<int>(run.truth.size()) - 1;
  g.AddLoopEdge(last - 2, last, Between(run.truth[last - 2], run.truth[last]));
  const OptimizeResult r = g.Optimize();
  EXPECT_TRUE(r.converged) << r.termination;
  EXPECT_EQ(r.num_loops, 1);
  EXPECT_TRUE(r.rejected.empty());
  const OdometryCalibration c = g.OdometryCalibrations().at(0);
  std::printf("with a loop: drift estimate %.5f rad/m (truth %.5f)\n", c[kCalibHeadingDrift],
              kDriftRadPerM);
  EXPECT_NEAR(c[kCalibHeadingDrift], kDriftRadPerM, 0.0005);
}

TEST(WallEdgeTest, WrongWallEdgesAreRejectedAndDoNotBendTheMap) {
  const OdometryRun run = Corridor();
  PoseGraph g;
  BuildOdometryChain(run, &g);
  const std::vector<int> walls = AddWallEdges(run, 20, &g);
  g.Optimize();
  const std::vector<EdgeReport> reports = g.EdgeReports();
  int rejected = 0, wrong = 0;
  for (const int index : walls) {
    const EdgeReport& report = reports[static_cast<std::size_t>(index)];
    EXPECT_EQ(report.kind, EdgeKind::kWall);
    wrong += report.to_id == 20;
    if (report.rejected) {
      EXPECT_EQ(report.to_id, 20) << report.from_id << " -> " << report.to_id;
      EXPECT_EQ(report.reason, "chi2");
      ++rejected;
    }
  }
  EXPECT_EQ(wrong, 5);
  EXPECT_GE(rejected, 4);  // 20 cm = 10 sigma: the wrong ones, not the right ones around them
  std::printf("with wrong wall edges: ATE %.2f cm\n", GraphAte(g, run.truth) * 100);
  EXPECT_LT(GraphAte(g, run.truth), 0.03);  // the path stays straight: 1.50 cm without them
  EXPECT_STREQ(EdgeKindName(EdgeKind::kWall), "wall");
}

}  // namespace
}  // namespace uwbsar
