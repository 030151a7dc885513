// Pairwise consistency of loop closures (the test at the heart of PCM, Mangelson
// et al. 2018, and of RRR, Latif et al. 2013): two loops (a, b) and (c, d) whose
// ends are close along the odometry chain (c near a, d near b) support each other
// when the cycle  a -> b (loop) -> d (odometry) -> c (loop, inverted) -> a (odometry)
// closes within its propagated covariance (chi2 test, 3 DOF).
//
// Why: a false loop into a part of the map that nothing else constrains (a dead-end
// corridor, the end of a run) bends that part without raising any residual, so no
// residual test can reject it. True loops come from revisits and arrive in groups that
// agree with each other; random false positives do not.
#pragma once

#include <Eigen/Core>
#include <vector>

#include "backend/pose_graph.h"

namespace uwbsar {

struct LoopSupportOptions {
  int window_nodes = 10;          ///< odometry steps between corresponding loop ends, at most
  double max_cycle_chi2 = 16.27;  ///< a cycle with a larger chi2 does not count as support
};

/// For every edge: the number of other loops consistent with it (loops), or -1 (odometry).
/// Edges are given with their information; odometry edges form the chain.
std::vector<int> CountLoopSupport(const std::vector<PoseGraphEdge>& edges,
                                  const LoopSupportOptions& options);

/// A pose with first-order covariance of a right perturbation T * exp(xi), xi = (x, y, yaw).
struct UncertainPose2 {
  Pose2 T;
  Eigen::Matrix3d covariance = Eigen::Matrix3d::Zero();
};

/// The measurement of an edge as an uncertain pose (covariance = information^-1).
UncertainPose2 EdgeAsUncertainPose(const PoseGraphEdge& edge);
UncertainPose2 Compose(const UncertainPose2& a_b, const UncertainPose2& b_c);
UncertainPose2 Inverse(const UncertainPose2& a_b);

}  // namespace uwbsar
