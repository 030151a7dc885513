// Relative-pose measurements with covariance, composed and inverted: what folding a node out of
// the pose graph (PoseGraph::RemoveNode) needs. The covariance is over the pose graph's own error
// (backend/se2_edge_cost.h): the translation of T_a_b in a's frame and the yaw, both additive;
// first-order propagation through the composition, as the edges' errors are independent.
#pragma once

#include <Eigen/Core>

#include "core/pose2.h"

namespace uwbsar {

/// A measured pose of `b` in the frame of `a` with the covariance of its error.
struct RelativePose {
  Pose2 T_a_b;
  Eigen::Matrix3d covariance = Eigen::Matrix3d::Identity();
};

/// T_b_a and its covariance.
RelativePose InvertRelativePose(const RelativePose& ab);

/// T_a_c = T_a_b * T_b_c with the covariance of independent errors on both.
RelativePose ComposeRelativePoses(const RelativePose& ab, const RelativePose& bc);

/// Two independent measurements of the same T_a_b fused (the error is linear in the measured
/// translation and yaw, so the information-weighted mean is exact; yaw taken near x's).
RelativePose FuseRelativePoses(const RelativePose& x, const RelativePose& y);

}  // namespace uwbsar
