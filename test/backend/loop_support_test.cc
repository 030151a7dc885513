#include "backend/loop_support.h"

#include <gtest/gtest.h>

namespace uwbsar {
namespace {

PoseGraphEdge Edge(int a, int b, const Pose2& T, EdgeKind kind) {
  PoseGraphEdge e;
  e.from_id = a;
  e.to_id = b;
  e.T_from_to = T;
  e.kind = kind;
  e.information = Eigen::Vector3d(100, 100, 400).asDiagonal();
  return e;
}

/// A straight corridor driven forward then back: nodes 0..9 out, 10..19 return.
std::vector<Pose2> Corridor() {
  std::vector<Pose2> poses;
  for (int k = 0; k < 10; ++k) poses.push_back({static_cast<double>(k), 0.0, 0.0});
  for (int k = 0; k < 10; ++k) poses.push_back({9.0 - k, 0.5, M_PI});
  return poses;
}

std::vector<PoseGraphEdge> OdometryOf(const std::vector<Pose2>& poses) {
  std::vector<PoseGraphEdge> edges;
  for (std::size_t k = 1; k < poses.size(); ++k) {
    edges.push_back(Edge(static_cast<int>(k - 1), static_cast<int>(k),
                         Between(poses[k - 1], poses[k]), EdgeKind::kOdometry));
  }
  return edges;
}

TEST(LoopSupportTest, AgreeingNeighbouringLoopsSupportEachOther) {
  const auto poses = Corridor();
  auto edges = OdometryOf(poses);
  for (int k : {12, 13, 14}) {  // return node k sees outbound node 19 - k
    edges.push_back(Edge(k, 19 - k, Between(poses[k], poses[19 - k]), EdgeKind::kLoop));
  }
  const std::vector<int> support = CountLoopSupport(edges, {});
  ASSERT_EQ(support.size(), edges.size());
  EXPECT_EQ(support[0], -1);  // odometry
  EXPECT_EQ(support[edges.size() - 1], 2);
  EXPECT_EQ(support[edges.size() - 2], 2);
}

TEST(LoopSupportTest, ContradictingOrDistantLoopsGiveNoSupport) {
  const auto poses = Corridor();
  auto edges = OdometryOf(poses);
  edges.push_back(Edge(12, 7, Between(poses[12], poses[7]), EdgeKind::kLoop));
  Pose2 wrong = Between(poses[13], poses[6]);
  wrong.x_m += 1.0;  // 1 m off with sigma 0.1 m
  edges.push_back(Edge(13, 6, wrong, EdgeKind::kLoop));
  const std::vector<int> support = CountLoopSupport(edges, {});
  EXPECT_EQ(support[edges.size() - 2], 0);
  EXPECT_EQ(support[edges.size() - 1], 0);
  LoopSupportOptions narrow;
  narrow.window_nodes = 0;  // the loops' ends are one node apart
  edges.back().T_from_to = Between(poses[13], poses[6]);
  EXPECT_EQ(CountLoopSupport(edges, {})[edges.size() - 1], 1);
  EXPECT_EQ(CountLoopSupport(edges, narrow)[edges.size() - 1], 0);
}

TEST(LoopSupportTest, CovarianceGrowsAlongAComposedChain) {
  UncertainPose2 step;
  step.T = {1.0, 0.0, 0.1};
  step.covariance = Eigen::Vector3d(0.01, 0.01, 0.001).asDiagonal();
  UncertainPose2 chain;
  double previous = 0.0;
  for (int k = 0; k < 5; ++k) {
    chain = Compose(chain, step);
    EXPECT_GT(chain.covariance.trace(), previous);
    previous = chain.covariance.trace();
  }
  const UncertainPose2 back = Compose(chain, Inverse(chain));
  EXPECT_NEAR(back.T.x_m, 0.0, 1e-12);
  EXPECT_NEAR(back.T.yaw_rad, 0.0, 1e-12);
}

}  // namespace
}  // namespace uwbsar
