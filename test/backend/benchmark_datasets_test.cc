// The backend on the standard 2-D pose-graph datasets (full size;
// labelled integration). The figures are printed for the report.
#include <gtest/gtest.h>

#include <cstdio>
#include <filesystem>
#include <opencv2/imgcodecs.hpp>

#include "backend/g2o_io.h"
#include "backend/graph_plot.h"
#include "backend/pose_graph.h"
#include "backend/trajectory_metrics.h"
#include "eval/false_loops.h"
#include "test/shared_data.h"

namespace uwbsar {
namespace {

// The public data sets are read where they lie (test/shared_data.h), never copied.
const std::string kData = testing::SharedDataPath("posegraph/");

double AteOf(const PoseGraph& g, const std::vector<Pose2>& truth) {
  std::vector<Pose2> est;
  for (const auto& [id, p] : g.GetPoses()) est.push_back(p);
  return ComputeAte(est, truth).rmse_m;
}

BackendConfig PlainLeastSquares() {
  BackendConfig c;
  c.robust_loss = RobustLoss::kNone;
  c.max_rejection_rounds = 0;
  c.min_loop_support = 0;
  return c;
}

class M3500Test : public ::testing::Test {
 protected:
  void SetUp() override {
    UWBSAR_NEED_SHARED_DATA("posegraph/manhattanOlson3500.g2o");
    UWBSAR_NEED_SHARED_DATA("posegraph/manhattanOlson3500_groundtruth.txt");
    file_ = ReadG2o(kData + "manhattanOlson3500.g2o");
    truth_ = ReadGroundTruthChain(kData + "manhattanOlson3500_groundtruth.txt");
  }
  G2oGraph file_;
  std::vector<Pose2> truth_;
};

TEST_F(M3500Test, ConvergesFromOdometryToThePlainLeastSquaresSolution) {
  PoseGraph robust;
  LoadIntoPoseGraph(file_, &robust);
  const OptimizeResult r = robust.Optimize();
  PoseGraph plain(PlainLeastSquares());
  LoadIntoPoseGraph(file_, &plain);
  const OptimizeResult p = plain.Optimize();
  const double ate = AteOf(robust, truth_), ate_plain = AteOf(plain, truth_);
  std::vector<Pose2> initial;
  for (const G2oVertex& v : file_.vertices) initial.push_back(v.T_world_node);
  std::printf(
      "M3500: %s, %d iterations, %d solves, cost %.4f -> %.6f (plain LS %.6f), %.3f s, "
      "ATE %.6f m (plain LS %.6f m, odometry %.4f m), rejected %zu\n",
      r.termination.c_str(), r.iterations, r.solves, r.initial_cost, r.final_cost, p.final_cost,
      r.solve_time_s, ate, ate_plain, ComputeAte(initial, truth_).rmse_m, r.rejected.size());
  EXPECT_TRUE(r.converged) << r.termination;
  EXPECT_TRUE(p.converged) << p.termination;
  EXPECT_TRUE(r.rejected.empty());
  EXPECT_NEAR(r.final_cost, p.final_cost, 1e-6 * p.final_cost);
  EXPECT_NEAR(ate, ate_plain, 1e-3 * ate_plain);
}

void ExpectFalseLoopsRejected(const G2oGraph& clean, const std::vector<Pose2>& truth, int count,
                              std::uint32_t seed) {
  PoseGraph reference;
  LoadIntoPoseGraph(clean, &reference);
  reference.Optimize();
  const double clean_ate = AteOf(reference, truth);

  G2oGraph file = clean;
  FalseLoopOptions options;
  options.count = count;
  options.seed = seed;
  const std::vector<std::size_t> false_loops = AddRandomFalseLoops(&file, options);
  PoseGraph robust;
  LoadIntoPoseGraph(file, &robust);
  const OptimizeResult r = robust.Optimize();
  const std::vector<EdgeReport> reports = robust.EdgeReports();
  int rejected_false = 0;
  for (const std::size_t i : false_loops) {
    // Each injected loop really is false: far from the truth's relative pose.
    const G2oEdge& e = file.edges[i];
    const Pose2 err = Between(Between(truth[static_cast<std::size_t>(e.from_id)],
                                      truth[static_cast<std::size_t>(e.to_id)]),
                              e.T_from_to);
    EXPECT_TRUE(std::hypot(err.x_m, err.y_m) > 1.0 || std::abs(err.yaw_rad) > 0.3) << i;
    EXPECT_TRUE(reports[i].rejected) << "false loop " << e.from_id << " -> " << e.to_id;
    rejected_false += reports[i].rejected;
  }
  PoseGraph plain(PlainLeastSquares());
  LoadIntoPoseGraph(file, &plain);
  plain.Optimize();
  const double ate = AteOf(robust, truth);
  std::printf(
      "M3500 + %d false loops (seed %u): %s, %.3f s, %d of %d false loops rejected, "
      "%zu loops rejected in all, ATE %.6f m (clean %.6f m, plain LS %.3f m)\n",
      count, seed, r.termination.c_str(), r.solve_time_s, rejected_false, count, r.rejected.size(),
      ate, clean_ate, AteOf(plain, truth));
  EXPECT_TRUE(r.converged) << r.termination;
  EXPECT_LE(ate, 1.1 * clean_ate);
  EXPECT_GT(AteOf(plain, truth), 2.0 * clean_ate);  // the false loops do matter
}

TEST_F(M3500Test, TwentyFalseLoopsAreAllRejected) {
  ExpectFalseLoopsRejected(file_, truth_, 20, 1);
  ExpectFalseLoopsRejected(file_, truth_, 20, 2);
}

TEST_F(M3500Test, HundredFalseLoopsAreAllRejected) {
  ExpectFalseLoopsRejected(file_, truth_, 100, 1);
  ExpectFalseLoopsRejected(file_, truth_, 100, 5);
}

TEST(MitBTest, ChordalStartReachesTheBasinThatSatisfiesEveryLoop) {
  UWBSAR_NEED_SHARED_DATA("posegraph/input_MITb_g2o.g2o");
  const G2oGraph file = ReadG2o(kData + "input_MITb_g2o.g2o");
  // From the file's guess, plain Levenberg-Marquardt ends in a wrong basin.
  PoseGraph from_guess(PlainLeastSquares());
  LoadIntoPoseGraph(file, &from_guess);
  const OptimizeResult g = from_guess.Optimize();

  BackendConfig c;
  c.initialization = GraphInitialization::kChordal;
  c.min_loop_support = 0;  // every MIT-B loop is a lone one (no neighbouring loops)
  PoseGraph graph(c);
  LoadIntoPoseGraph(file, &graph);
  const OptimizeResult r = graph.Optimize();
  double max_loop_chi2 = 0.0;
  for (const EdgeReport& e : graph.EdgeReports()) max_loop_chi2 = std::max(max_loop_chi2, e.chi2);
  std::printf(
      "MIT-B: from the guess: %s cost %.2f; chordal start: %s, %d iterations, cost %.4f -> "
      "%.6f, %.3f s, rejected %zu, largest edge chi2 %.3f\n",
      g.termination.c_str(), g.final_cost, r.termination.c_str(), r.iterations, r.initial_cost,
      r.final_cost, r.solve_time_s, r.rejected.size(), max_loop_chi2);
  EXPECT_TRUE(r.converged) << r.termination;
  EXPECT_TRUE(r.rejected.empty());
  EXPECT_LT(max_loop_chi2, c.loop_rejection_chi2);
  EXPECT_LT(r.final_cost, 0.05 * g.final_cost);
  const std::string png = (std::filesystem::temp_directory_path() / "uwbsar_mitb.png").string();
  cv::imwrite(png, PlotPoseGraph(graph.GetPoses(), graph.Edges(), graph.EdgeReports()));
  std::printf("MIT-B trajectory: %s\n", png.c_str());
}

}  // namespace
}  // namespace uwbsar
