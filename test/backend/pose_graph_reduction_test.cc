// Folding nodes out of the pose graph (PoseGraph::RemoveNode) and the covariance algebra behind
// it (backend/edge_composition.h).
#include <gtest/gtest.h>

#include <Eigen/Cholesky>
#include <Eigen/LU>
#include <random>

#include "backend/edge_composition.h"
#include "backend/pose_graph.h"
#include "core/errors.h"

namespace uwbsar {
namespace {

Pose2 Perturbed(const Pose2& T, const Eigen::Vector3d& e) {
  return Pose2{T.x_m + e.x(), T.y_m + e.y(), T.yaw_rad + e.z()};
}

Eigen::Vector3d ErrorOf(const Pose2& measured, const Pose2& mean) {
  return {measured.x_m - mean.x_m, measured.y_m - mean.y_m,
          NormalizeAngle(measured.yaw_rad - mean.yaw_rad)};
}

/// Empirical covariance of f(ab + e1, bc + e2) against the propagated one.
TEST(EdgeCompositionTest, PropagatedCovarianceMatchesSampledErrors) {
  const RelativePose ab{{1.5, -0.4, 0.7}, Eigen::Vector3d(1e-4, 4e-4, 2e-4).asDiagonal()};
  const RelativePose bc{{2.0, 0.8, -1.2}, Eigen::Vector3d(9e-4, 1e-4, 5e-4).asDiagonal()};
  const RelativePose ac = ComposeRelativePoses(ab, bc);
  const RelativePose ba = InvertRelativePose(ab);
  std::mt19937_64 rng(7);
  std::normal_distribution<double> n01;
  const Eigen::Matrix3d La = ab.covariance.llt().matrixL(), Lb = bc.covariance.llt().matrixL();
  Eigen::Matrix3d sum_ac = Eigen::Matrix3d::Zero(), sum_ba = Eigen::Matrix3d::Zero();
  const int n = 20000;
  for (int i = 0; i < n; ++i) {
    const Eigen::Vector3d e1 = La * Eigen::Vector3d(n01(rng), n01(rng), n01(rng));
    const Eigen::Vector3d e2 = Lb * Eigen::Vector3d(n01(rng), n01(rng), n01(rng));
    const Eigen::Vector3d dac =
        ErrorOf(Perturbed(ab.T_a_b, e1) * Perturbed(bc.T_a_b, e2), ac.T_a_b);
    const Eigen::Vector3d dba = ErrorOf(Perturbed(ab.T_a_b, e1).Inverse(), ba.T_a_b);
    sum_ac += dac * dac.transpose();
    sum_ba += dba * dba.transpose();
  }
  for (int r = 0; r < 3; ++r) {
    for (int c = 0; c < 3; ++c) {
      EXPECT_NEAR(sum_ac(r, c) / n, ac.covariance(r, c), 0.05 * ac.covariance.norm())
          << r << "," << c;
      EXPECT_NEAR(sum_ba(r, c) / n, ba.covariance(r, c), 0.05 * ba.covariance.norm())
          << r << "," << c;
    }
  }
  EXPECT_NEAR(ac.T_a_b.x_m, (ab.T_a_b * bc.T_a_b).x_m, 1e-12);
}

/// A ring of `n` nodes 1 m apart turning left at every 5th, with odometry whose yaw is biased,
/// and one loop closing the ring.
void BuildRing(PoseGraph* graph, int n, double yaw_bias_rad, std::vector<Pose2>* truth) {
  Pose2 p, odo;
  for (int k = 0; k < n; ++k) {
    truth->push_back(p);
    graph->AddNode(k, odo);
    if (k == 0) graph->FixNode(0);
    const Pose2 step = (k % 5 == 4) ? Pose2{1.0, 0.0, M_PI / 2} : Pose2{1.0, 0.0, 0.0};
    if (k + 1 < n) {
      const Pose2 measured{step.x_m, step.y_m, step.yaw_rad + yaw_bias_rad};
      odo = odo * measured;
      p = p * step;
    }
  }
  for (int k = 0; k + 1 < n; ++k) {
    const Pose2 step = (k % 5 == 4) ? Pose2{1.0, 0.0, M_PI / 2} : Pose2{1.0, 0.0, 0.0};
    graph->AddOdometryEdge(k, k + 1, {step.x_m, step.y_m, step.yaw_rad + yaw_bias_rad}, -1);
  }
}

TEST(PoseGraphReductionTest, RemovingANodeKeepsTheSolutionAndFoldsItsEdges) {
  BackendConfig config;
  config.function_tolerance = 1e-16;  // solved to the minimum: removal keeps it exactly
  config.max_iterations = 200;
  PoseGraph graph(config);
  std::vector<Pose2> truth;
  BuildRing(&graph, 20, 0.01, &truth);
  graph.AddLoopEdge(19, 0, Between(truth[19], truth[0]));
  graph.AddLoopEdge(7, 2, Between(truth[7], truth[2]));
  graph.Optimize();
  graph.Optimize();  // a warm solve: the loops are past their support gate
  for (const EdgeReport& r : graph.EdgeReports()) EXPECT_FALSE(r.rejected) << r.index;
  const std::map<int, Pose2> before = graph.GetPoses();
  const int edges_before = graph.NumEdges();

  // A node on the chain (odometry in and out) folds exactly to first order: a tenth of a
  // millimetre.
  graph.RemoveNode(12);
  graph.Optimize();
  for (const auto& [id, p] : graph.GetPoses()) {
    EXPECT_NEAR(p.x_m, before.at(id).x_m, 2e-4) << id;
    EXPECT_NEAR(p.y_m, before.at(id).y_m, 2e-4) << id;
    EXPECT_NEAR(p.yaw_rad, before.at(id).yaw_rad, 5e-5) << id;
  }
  EXPECT_EQ(graph.NumEdges(), edges_before - 1);

  const std::map<int, Pose2> solved = graph.GetPoses();
  Pose2 T_hub_node;
  const int hub = graph.RemoveNode(7, &T_hub_node);  // odometry 6-7, 7-8 and the loop 7-2
  EXPECT_TRUE(hub == 6 || hub == 8) << hub;          // odometry ties it more strongly than the loop
  EXPECT_FALSE(graph.HasNode(7));
  EXPECT_EQ(graph.NumNodes(), 18);
  EXPECT_EQ(graph.NumEdges(), edges_before - 2);  // three edges in, two folded ones out
  int marginal = 0;
  for (const PoseGraphEdge& e : graph.Edges()) {
    EXPECT_NE(e.from_id, 7);
    EXPECT_NE(e.to_id, 7);
    if (e.kind == EdgeKind::kMarginal) {
      ++marginal;
      EXPECT_TRUE(e.to_id == hub || e.to_id == 11 || e.to_id == 13);
    }
  }
  EXPECT_EQ(marginal, 3);  // with 11 -> 13
  EXPECT_EQ(graph.Edges().size(), graph.EdgeReports().size());
  const Pose2 expected = Between(solved.at(hub), solved.at(7));
  EXPECT_NEAR(T_hub_node.x_m, expected.x_m, 1e-9);
  EXPECT_NEAR(T_hub_node.y_m, expected.y_m, 1e-9);

  // A node with a loop folds approximately (the star drops a correlation): sub-millimetre.
  graph.Optimize();
  for (const auto& [id, p] : graph.GetPoses()) {
    EXPECT_NEAR(p.x_m, before.at(id).x_m, 1e-3) << id;
    EXPECT_NEAR(p.y_m, before.at(id).y_m, 1e-3) << id;
    EXPECT_NEAR(p.yaw_rad, before.at(id).yaw_rad, 1e-3) << id;
  }
}

TEST(PoseGraphReductionTest, ARemovedNodesConstraintsStillCorrectTheMapLater) {
  // The full graph and a reduced one see the same edges; the reduced one loses nodes 3..16
  // (every other one) after a first solve, then both get the loop that closes the ring.
  PoseGraph full, reduced;
  std::vector<Pose2> truth, unused;
  BuildRing(&full, 20, 0.02, &truth);
  BuildRing(&reduced, 20, 0.02, &unused);
  for (PoseGraph* g : {&full, &reduced}) g->Optimize();
  for (int id = 3; id <= 16; id += 2) reduced.RemoveNode(id);
  for (PoseGraph* g : {&full, &reduced}) {
    g->AddLoopEdge(19, 0, Between(truth[19], truth[0]));
    g->Optimize();
  }
  const std::map<int, Pose2> a = full.GetPoses(), b = reduced.GetPoses();
  double worst_m = 0.0, worst_odometry_m = 0.0;
  for (const auto& [id, p] : b) {
    worst_m = std::max(worst_m, std::hypot(p.x_m - a.at(id).x_m, p.y_m - a.at(id).y_m));
    worst_odometry_m =
        std::max(worst_odometry_m, std::hypot(p.x_m - truth[id].x_m, p.y_m - truth[id].y_m));
  }
  // Linearised at the first solution, the folded edges pull the remaining nodes as the
  // removed ones did: millimetres next to the loop's correction of decimetres.
  EXPECT_LT(worst_m, 0.01);
  EXPECT_GT(worst_odometry_m, 0.05);
}

TEST(PoseGraphReductionTest, RefusesFixedUnknownAndUnsolvedNodes) {
  PoseGraph graph;
  std::vector<Pose2> truth;
  BuildRing(&graph, 5, 0.0, &truth);
  EXPECT_THROW(graph.RemoveNode(2), InputError);  // never solved
  graph.Optimize();
  EXPECT_THROW(graph.RemoveNode(0), InputError);   // the gauge
  EXPECT_THROW(graph.RemoveNode(42), InputError);  // unknown
  EXPECT_NO_THROW(graph.RemoveNode(4));            // the end of the chain: one neighbour
  EXPECT_EQ(graph.NumEdges(), 3);
}

/// A saved map 0..5, frozen, and a new run 10..13 with biased odometry, tied to it by loops
/// from 12 to node 3 and (with `loop_to_2`) from 10 to node 2.
void BuildFrozenMapAndNewRun(PoseGraph* graph, bool loop_to_2) {
  std::vector<Pose2> truth;
  BuildRing(graph, 6, 0.0, &truth);
  for (int k = 1; k < 6; ++k) graph->FixNode(k);
  Pose2 odo{2.0, 0.6, 0.0};
  for (int k = 10; k <= 13; ++k) {
    graph->AddNode(k, odo);
    odo = odo * Pose2{0.5, 0.0, 0.03};
  }
  for (int k = 10; k < 13; ++k) graph->AddOdometryEdge(k, k + 1, {0.5, 0.0, 0.03}, -1);
  if (loop_to_2) graph->AddLoopEdge(2, 10, Between(truth[2], Pose2{2.0, 0.5, 0.0}));
  graph->AddLoopEdge(3, 12, Between(truth[3], Pose2{3.0, 0.5, 0.0}));
}

TEST(PoseGraphReductionTest, AFrozenMapsNodeFoldsIntoAFixedNeighbourAndKeepsItsPull) {
  BackendConfig config;
  config.function_tolerance = 1e-16;
  config.max_iterations = 200;
  PoseGraph graph(config);
  BuildFrozenMapAndNewRun(&graph, true);
  graph.Optimize();
  const std::map<int, Pose2> before = graph.GetPoses();
  Pose2 T_hub_node;
  const int hub = graph.RemoveNode(2, &T_hub_node);
  EXPECT_TRUE(hub == 1 || hub == 3) << hub;
  const std::vector<int> fixed = graph.FixedNodes();
  EXPECT_EQ(std::count(fixed.begin(), fixed.end(), 2), 0);
  EXPECT_NEAR(T_hub_node.x_m, Between(before.at(hub), before.at(2)).x_m, 1e-12);
  graph.Optimize();
  const std::map<int, Pose2> after = graph.GetPoses();
  // Not exactly: the loop was robust and the folded edge is plain least squares, so the pull
  // of a loop that disagrees with the odometry changes a little (0.2 mm here).
  for (int k = 10; k <= 13; ++k) {
    EXPECT_NEAR(after.at(k).x_m, before.at(k).x_m, 5e-4) << k;
    EXPECT_NEAR(after.at(k).y_m, before.at(k).y_m, 5e-4) << k;
    EXPECT_NEAR(after.at(k).yaw_rad, before.at(k).yaw_rad, 5e-4) << k;
  }
  // Dropping the node's loop instead of folding it moves the new run: the test can fail.
  PoseGraph dropped(config);
  BuildFrozenMapAndNewRun(&dropped, false);
  dropped.Optimize();
  const Pose2 moved = dropped.GetPose(10);
  EXPECT_GT(std::hypot(moved.x_m - before.at(10).x_m, moved.y_m - before.at(10).y_m), 5e-3);
  // A fixed node with no fixed neighbour (the gauge of a run) cannot be folded.
  PoseGraph gauge;
  std::vector<Pose2> truth;
  BuildRing(&gauge, 4, 0.0, &truth);
  gauge.Optimize();
  EXPECT_THROW(gauge.RemoveNode(0), InputError);
}

TEST(PoseGraphReductionTest, FoldedEdgesBetweenTheSamePairMerge) {
  // A chain 0..5 and a node 6 seen from 1 and 3 by loops. Removing 2 folds 1-2-3 into one
  // edge between 1 and 3; removing 6 folds 1-6-3 into another between them, which merges.
  PoseGraph graph;
  std::vector<Pose2> truth;
  BuildRing(&graph, 6, 0.0, &truth);
  const Pose2 six{2.0, 1.0, 0.3};
  graph.AddNode(6, six);
  graph.AddLoopEdge(1, 6, Between(truth[1], six));
  graph.AddLoopEdge(3, 6, Between(truth[3], six));
  graph.Optimize();
  graph.RemoveNode(2);
  const int after_first = graph.NumEdges();
  graph.RemoveNode(6);
  int marginal_1_3 = 0;
  for (const PoseGraphEdge& e : graph.Edges()) {
    const bool pair = (e.from_id == 1 && e.to_id == 3) || (e.from_id == 3 && e.to_id == 1);
    if (pair && e.kind == EdgeKind::kMarginal) ++marginal_1_3;
  }
  EXPECT_EQ(marginal_1_3, 1);
  EXPECT_EQ(graph.NumEdges(), after_first - 2);  // two loops out, nothing new
}

}  // namespace
}  // namespace uwbsar
