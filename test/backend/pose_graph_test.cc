#include "backend/pose_graph.h"

#include <gtest/gtest.h>

#include <atomic>
#include <random>
#include <thread>

#include "backend/g2o_io.h"
#include "backend/odometry_calibration.h"
#include "backend/trajectory_metrics.h"
#include "core/errors.h"
#include "test/shared_data.h"

namespace uwbsar {
namespace {

/// The first 300 poses of M3500 (public data set, read in place, see test/shared_data.h):
/// their vertices, the edges among them and the ground-truth chain.
struct M3500Prefix {
  G2oGraph graph;
  std::vector<Pose2> truth;
};
M3500Prefix LoadM3500Prefix(int num_poses) {
  M3500Prefix out;
  const G2oGraph full = ReadG2o(testing::SharedDataPath("posegraph/manhattanOlson3500.g2o"));
  for (const G2oVertex& v : full.vertices) {
    if (v.id < num_poses) out.graph.vertices.push_back(v);
  }
  for (const G2oEdge& e : full.edges) {
    if (e.from_id < num_poses && e.to_id < num_poses) out.graph.edges.push_back(e);
  }
  for (int id : full.fixed_ids) {
    if (id < num_poses) out.graph.fixed_ids.push_back(id);
  }
  out.truth =
      ReadGroundTruthChain(testing::SharedDataPath("posegraph/manhattanOlson3500_groundtruth.txt"));
  out.truth.resize(static_cast<std::size_t>(num_poses));
  return out;
}

/// A robot driving around a 10-node square twice: truth, and odometry with a yaw bias.
struct SquareRun {
  std::vector<Pose2> truth;
  std::vector<Pose2> odometry_steps;  // truth step with a yaw bias
};

SquareRun MakeSquareRun(int laps, double yaw_bias_rad = 0.02) {
  SquareRun run;
  Pose2 p;
  for (int k = 0; k < 4 * 5 * laps; ++k) {
    run.truth.push_back(p);
    const Pose2 step = (k % 5 == 4) ? Pose2{1.0, 0.0, M_PI / 2} : Pose2{1.0, 0.0, 0.0};
    run.odometry_steps.push_back({step.x_m, step.y_m, step.yaw_rad + yaw_bias_rad});
    p = p * step;
  }
  return run;
}

/// Builds the square graph with odometry edges and a loop from each node of lap 2 to lap 1.
void BuildSquare(const SquareRun& run, PoseGraph* g, bool with_loops = true) {
  Pose2 odom;
  for (std::size_t k = 0; k < run.truth.size(); ++k) {
    g->AddNode(static_cast<int>(k), odom);
    if (k > 0) {
      g->AddOdometryEdge(static_cast<int>(k - 1), static_cast<int>(k), run.odometry_steps[k - 1]);
    }
    odom = odom * run.odometry_steps[k];
  }
  for (std::size_t k = 20; with_loops && k < run.truth.size(); ++k) {
    g->AddLoopEdge(static_cast<int>(k), static_cast<int>(k - 20),
                   Between(run.truth[k], run.truth[k - 20]));
  }
}

double AteOf(const PoseGraph& g, const std::vector<Pose2>& truth) {
  std::vector<Pose2> est;
  for (const auto& [id, p] : g.GetPoses()) est.push_back(p);
  return ComputeAte(est, truth).rmse_m;
}

TEST(PoseGraphTest, LoopsCorrectOdometryDriftAndTheFirstNodeStaysFixed) {
  const SquareRun run = MakeSquareRun(2);
  PoseGraph g;
  BuildSquare(run, &g);
  const double ate_before = AteOf(g, run.truth);
  const OptimizeResult r = g.Optimize();
  EXPECT_TRUE(r.converged) << r.termination;
  EXPECT_TRUE(r.rejected.empty());
  EXPECT_LT(r.final_cost, r.initial_cost);
  EXPECT_GT(ate_before, 0.3);
  EXPECT_LT(AteOf(g, run.truth), 0.5 * ate_before);
  const Pose2 first = g.GetPose(0);
  EXPECT_EQ(first.x_m, 0.0);
  EXPECT_EQ(first.yaw_rad, 0.0);
}

TEST(PoseGraphTest, OdometryInformationIsScaledByTravelledDistance) {
  BackendConfig c;
  c.odometry_xy_information = 50;
  c.odometry_yaw_information = 20;
  c.odometry_min_distance_m = 0.1;
  PoseGraph g(c);
  for (int k = 0; k < 3; ++k) g.AddNode(k, {});
  g.AddOdometryEdge(0, 1, {2.0, 0.0, 0.0});
  g.AddOdometryEdge(1, 2, {0.0, 0.01, 0.0});
  const auto edges = g.Edges();
  EXPECT_DOUBLE_EQ(edges[0].information(0, 0), 25.0);
  EXPECT_DOUBLE_EQ(edges[0].information(2, 2), 10.0);
  EXPECT_DOUBLE_EQ(edges[1].information(1, 1), 500.0);  // clamped at 0.1 m
  EXPECT_EQ(edges[0].kind, EdgeKind::kOdometry);
}

TEST(PoseGraphTest, BadElementsThrowAndLeaveTheGraphUntouched) {
  PoseGraph g;
  g.AddNode(0, {});
  g.AddNode(1, {1, 0, 0});
  g.AddOdometryEdge(0, 1, {1, 0, 0});
  PoseGraphEdge e;
  e.from_id = 0;
  e.to_id = 5;
  EXPECT_THROW(g.AddEdge(e), InputError);  // unknown node
  e.to_id = 0;
  EXPECT_THROW(g.AddEdge(e), InputError);  // self edge
  e.to_id = 1;
  e.information = Eigen::Vector3d(1, -1, 1).asDiagonal();
  EXPECT_THROW(g.AddEdge(e), InputError);  // not positive definite
  e.information = Eigen::Matrix3d::Identity();
  e.T_from_to.x_m = std::nan("");
  EXPECT_THROW(g.AddEdge(e), InputError);      // NaN measurement
  EXPECT_THROW(g.AddNode(1, {}), InputError);  // duplicate
  EXPECT_THROW(g.AddNode(2, {std::nan(""), 0, 0}), InputError);
  EXPECT_THROW(g.FixNode(9), InputError);
  EXPECT_EQ(g.NumNodes(), 2);
  EXPECT_EQ(g.NumEdges(), 1);
  const OptimizeResult r = g.Optimize();
  EXPECT_TRUE(r.converged) << r.termination;
  EXPECT_EQ(r.num_edges, 1);
  EXPECT_NEAR(g.GetPose(1).x_m, 1.0, 1e-9);
}

TEST(PoseGraphTest, IncrementalOptimisationMatchesBatch) {
  const SquareRun run = MakeSquareRun(2);
  PoseGraph batch;
  BuildSquare(run, &batch);
  batch.Optimize();

  PoseGraph inc;
  Pose2 odom;
  int solves = 0;
  for (std::size_t k = 0; k < run.truth.size(); ++k) {
    const int id = static_cast<int>(k);
    inc.AddNode(id, odom);
    if (k > 0) inc.AddOdometryEdge(id - 1, id, run.odometry_steps[k - 1]);
    if (k >= 20) inc.AddLoopEdge(id, id - 20, Between(run.truth[k], run.truth[k - 20]));
    if (k % 3 == 0) {
      EXPECT_TRUE(inc.Optimize().converged);
      ++solves;
    }
    odom = odom * run.odometry_steps[k];
  }
  inc.Optimize();
  EXPECT_GT(solves, 5);
  for (const auto& [id, p] : batch.GetPoses()) {
    const Pose2 q = inc.GetPose(id);
    // Both stop at the solver's tolerance on a flat cost: equal to a tenth of a millimetre.
    EXPECT_NEAR(p.x_m, q.x_m, 1e-4) << id;
    EXPECT_NEAR(p.y_m, q.y_m, 1e-4) << id;
  }
}

TEST(PoseGraphTest, NodeAddedAfterASolveIsSeededOnTheCorrectedTrajectory) {
  const SquareRun run = MakeSquareRun(2);
  PoseGraph g;
  BuildSquare(run, &g);
  g.Optimize();
  const int last = static_cast<int>(run.truth.size()) - 1;
  g.AddNode(last + 1, {1000, 1000, 0});  // a stale guess
  g.AddOdometryEdge(last, last + 1, {1, 0, 0});
  g.Optimize();
  // The step as the trajectory's odometry calibration corrects it (the loops make it free).
  const Pose2 expected =
      g.GetPose(last) * CorrectedOdometryStep(g.OdometryCalibrations().at(0), Pose2{1, 0, 0});
  EXPECT_NEAR(g.GetPose(last + 1).x_m, expected.x_m, 1e-6);
  EXPECT_NEAR(g.GetPose(last + 1).y_m, expected.y_m, 1e-6);
}

TEST(PoseGraphTest, FalseLoopIsRejectedAndReportedWithItsChi2) {
  const SquareRun run = MakeSquareRun(2);
  PoseGraph clean;
  BuildSquare(run, &clean);
  clean.Optimize();
  PoseGraph g;
  BuildSquare(run, &g);
  const int bad = g.AddLoopEdge(30, 2, {0.5, 0.2, 1.0});  // places 30 next to 2: wrong
  const OptimizeResult r = g.Optimize();
  ASSERT_EQ(r.rejected.size(), 1u);
  EXPECT_EQ(r.rejected[0].index, bad);
  EXPECT_GT(r.rejected[0].chi2, g.config().loop_rejection_chi2);
  EXPECT_FALSE(r.rejected[0].reason.empty());
  EXPECT_NEAR(AteOf(g, run.truth), AteOf(clean, run.truth), 1e-6);
}

TEST(PoseGraphTest, WithoutRejectionAFalseLoopBendsTheMap) {
  // The counterpart of the test above: proves that the false loop matters.
  const SquareRun run = MakeSquareRun(2);
  BackendConfig c;
  c.robust_loss = RobustLoss::kNone;
  c.max_rejection_rounds = 0;
  c.min_loop_support = 0;
  PoseGraph clean(c);
  BuildSquare(run, &clean);
  clean.Optimize();
  PoseGraph g(c);
  BuildSquare(run, &g);
  g.AddLoopEdge(30, 2, {0.5, 0.2, 1.0});
  const OptimizeResult r = g.Optimize();
  EXPECT_TRUE(r.rejected.empty());
  EXPECT_GT(AteOf(g, run.truth), AteOf(clean, run.truth) + 0.1);
}

TEST(PoseGraphTest, LoneLoopIsHeldBackUntilTheMapConfirmsIt) {
  const SquareRun run = MakeSquareRun(2, 0.0);  // exact odometry: the map is right
  PoseGraph g;
  BuildSquare(run, &g, false);
  // A lone loop that agrees with the map is admitted...
  const int good = g.AddLoopEdge(35, 12, Between(run.truth[35], run.truth[12]));
  g.Optimize();
  EXPECT_FALSE(g.EdgeReports()[static_cast<std::size_t>(good)].rejected);
  EXPECT_EQ(g.EdgeReports()[static_cast<std::size_t>(good)].support, 0);
  // ...a lone loop that contradicts it is rejected as unsupported.
  const int bad = g.AddLoopEdge(36, 3, {0.0, 3.0, 0.0});
  const OptimizeResult r = g.Optimize();
  ASSERT_EQ(r.rejected.size(), 1u);
  EXPECT_EQ(r.rejected[0].index, bad);
  EXPECT_EQ(r.rejected[0].reason, "unsupported");
}

TEST(PoseGraphTest, ExplicitFixReplacesTheDefaultGauge) {
  PoseGraph g;
  g.AddNode(0, {});
  g.AddNode(1, {1, 0, 0});
  g.FixNode(1);
  g.AddOdometryEdge(0, 1, {2, 0, 0});
  g.Optimize();
  EXPECT_NEAR(g.GetPose(1).x_m, 1.0, 1e-12);
  EXPECT_NEAR(g.GetPose(0).x_m, -1.0, 1e-6);
}

TEST(PoseGraphTest, FrontendThreadCanAddWhileABackgroundThreadOptimises) {
  const SquareRun run = MakeSquareRun(4);
  // The run's odometry has a 1.1 deg/m heading bias: weigh it as such (the follow-on's 50),
  // not as the calibrated odometry of the defaults.
  BackendConfig config;
  config.odometry_xy_information = 50.0;
  config.odometry_yaw_information = 50.0;
  PoseGraph g(config);
  std::atomic<bool> done{false};
  std::atomic<int> solves{0};
  std::thread backend([&] {
    while (!done) {
      if (g.Optimize().num_nodes > 0) ++solves;
    }
  });
  Pose2 odom;
  for (std::size_t k = 0; k < run.truth.size(); ++k) {
    const int id = static_cast<int>(k);
    g.AddNode(id, odom);
    if (k > 0) g.AddOdometryEdge(id - 1, id, run.odometry_steps[k - 1]);
    if (k >= 20) g.AddLoopEdge(id, id - 20, Between(run.truth[k], run.truth[k - 20]));
    (void)g.GetPoses();
    odom = odom * run.odometry_steps[k];
    std::this_thread::sleep_for(std::chrono::microseconds(200));
  }
  done = true;
  backend.join();
  const OptimizeResult r = g.Optimize();
  EXPECT_GT(solves.load(), 0);
  EXPECT_EQ(r.num_nodes, static_cast<int>(run.truth.size()));
  EXPECT_TRUE(r.rejected.empty());
  EXPECT_LT(AteOf(g, run.truth), 0.05);
}

TEST(PoseGraphTest, M3500PrefixFromOdometryConvergesToPlainLeastSquares) {
  UWBSAR_NEED_SHARED_DATA("posegraph/manhattanOlson3500.g2o");
  UWBSAR_NEED_SHARED_DATA("posegraph/manhattanOlson3500_groundtruth.txt");
  const M3500Prefix prefix = LoadM3500Prefix(300);
  const G2oGraph& file = prefix.graph;
  const std::vector<Pose2>& truth = prefix.truth;
  PoseGraph robust;
  LoadIntoPoseGraph(file, &robust);
  const OptimizeResult r = robust.Optimize();
  EXPECT_TRUE(r.converged) << r.termination;
  EXPECT_TRUE(r.rejected.empty());
  BackendConfig plain_config;
  plain_config.robust_loss = RobustLoss::kNone;
  plain_config.max_rejection_rounds = 0;
  plain_config.min_loop_support = 0;
  PoseGraph plain(plain_config);
  LoadIntoPoseGraph(file, &plain);
  const OptimizeResult p = plain.Optimize();
  EXPECT_NEAR(r.final_cost, p.final_cost, 1e-6 * p.final_cost);
  std::vector<Pose2> initial;
  for (const G2oVertex& v : file.vertices) initial.push_back(v.T_world_node);
  const double ate = AteOf(robust, truth);
  EXPECT_NEAR(ate, AteOf(plain, truth), 1e-3 * ate);
  EXPECT_LT(ate, ComputeAte(initial, truth).rmse_m);
}

}  // namespace
}  // namespace uwbsar
