#include "backend/odometry_consistency.h"

#include <gtest/gtest.h>

#include "backend/pose_graph.h"

namespace uwbsar {
namespace {

PoseGraphEdge Edge(int a, int b, EdgeKind kind) {
  PoseGraphEdge e;
  e.from_id = a;
  e.to_id = b;
  e.kind = kind;
  return e;
}

TEST(OdometryConsistencyTest, NothingBlamedWhileOdometryFitsItsNoise) {
  const std::vector<PoseGraphEdge> edges = {Edge(0, 1, EdgeKind::kOdometry),
                                            Edge(1, 2, EdgeKind::kOdometry),
                                            Edge(0, 2, EdgeKind::kLoop)};
  const std::vector<SolvedEdge> solved = {
      {&edges[0], 3.0, true, -1}, {&edges[1], 29.0, true, -1}, {&edges[2], 50.0, true, 0}};
  double worst = 0.0;
  EXPECT_EQ(LoopToBlame(solved, 30.0, &worst), -1);
  EXPECT_DOUBLE_EQ(worst, 29.0);
}

TEST(OdometryConsistencyTest, BlamesTheLeastSupportedLoopSpanningTheWorstEdge) {
  std::vector<PoseGraphEdge> edges;
  for (int k = 0; k < 6; ++k) edges.push_back(Edge(k, k + 1, EdgeKind::kOdometry));
  edges.push_back(Edge(0, 6, EdgeKind::kLoop));  // 6: spans 2 -> 3, support 2
  edges.push_back(Edge(1, 4, EdgeKind::kLoop));  // 7: spans 2 -> 3, support 0
  edges.push_back(Edge(3, 6, EdgeKind::kLoop));  // 8: does not span 2 -> 3, support 0
  edges.push_back(Edge(5, 2, EdgeKind::kLoop));  // 9: spans it (reversed), rejected already
  std::vector<SolvedEdge> solved;
  for (const PoseGraphEdge& e : edges) solved.push_back({&e, 1.0, true, -1});
  solved[2].chi2 = 80.0;  // odometry 2 -> 3 bent far out of its noise
  solved[6].support = 2;
  solved[7].support = 0;
  solved[8].support = 0;
  solved[9].support = 0;
  solved[9].accepted = false;
  EXPECT_EQ(LoopToBlame(solved, 30.0), 7);
  solved[7].accepted = false;
  EXPECT_EQ(LoopToBlame(solved, 30.0), 6);
  solved[6].accepted = false;
  EXPECT_EQ(LoopToBlame(solved, 30.0), -1);  // no accepted loop spans it: nothing to blame
}

// A false loop between the two ends of a short chain, the only loop, far more confident
// than the odometry: it pulls the chain and fits itself (its own chi2 passes), while the
// chain's edges lie far outside their noise; the loop is rejected as inconsistent and the
// chain stays as measured.
TEST(OdometryConsistencyTest, PoseGraphRejectsALoopThatBendsAShortChain) {
  BackendConfig config;
  config.min_loop_support = 0;  // the loop alone: only the consistency test can catch it
  config.robust_loss = RobustLoss::kNone;
  PoseGraph graph(config);
  for (int k = 0; k <= 5; ++k) graph.AddNode(k, {static_cast<double>(k), 0.0, 0.0});
  for (int k = 0; k < 5; ++k) graph.AddOdometryEdge(k, k + 1, {1.0, 0.0, 0.0});
  PoseGraphEdge loop;
  loop.from_id = 0;
  loop.to_id = 5;
  loop.T_from_to = {4.0, 1.5, 0.3};  // 1.5 m and 17 deg off the 5 m of straight odometry
  loop.information = Eigen::Vector3d(1e8, 1e8, 1e8).asDiagonal();
  graph.AddEdge(loop);
  const OptimizeResult result = graph.Optimize();
  ASSERT_EQ(result.rejected.size(), 1u);
  EXPECT_EQ(result.rejected[0].reason, "inconsistent");
  EXPECT_NEAR(graph.GetPose(5).x_m, 5.0, 1e-6);
  EXPECT_NEAR(graph.GetPose(5).y_m, 0.0, 1e-6);

  BackendConfig off = config;
  off.max_odometry_chi2 = 0.0;
  PoseGraph unchecked(off);
  for (int k = 0; k <= 5; ++k) unchecked.AddNode(k, {static_cast<double>(k), 0.0, 0.0});
  for (int k = 0; k < 5; ++k) unchecked.AddOdometryEdge(k, k + 1, {1.0, 0.0, 0.0});
  unchecked.AddEdge(loop);
  unchecked.Optimize();
  EXPECT_GT(std::abs(unchecked.GetPose(5).y_m), 0.1);  // without the test the loop bends it
}

}  // namespace
}  // namespace uwbsar
