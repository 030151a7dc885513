// The SE(2) relative-pose residual of the pose graph (the model of Ceres's
// examples/slam/pose_graph_2d, written here with analytic Jacobians):
//   e = [ R_a^T (t_b - t_a) - t_ab ;  wrap(yaw_b - yaw_a - yaw_ab) ]
//   r = U e,  with U the upper Cholesky factor of the information (U^T U = Omega),
// so that |r|^2 = e^T Omega e is the edge's chi2. A pose parameter block is
// [x_m, y_m, yaw_rad]; yaw is not wrapped in the block, only in the residual.
#pragma once

#include <ceres/sized_cost_function.h>

#include <Eigen/Core>
#include <optional>

#include "core/pose2.h"

namespace uwbsar {

/// U with U^T U = information, or nothing when the information is not symmetric
/// positive definite (or not finite).
std::optional<Eigen::Matrix3d> SqrtInformation(const Eigen::Matrix3d& information);

/// The unweighted error e of measurement T_a_b between pose blocks a and b.
Eigen::Vector3d Se2Error(const double* pose_a, const double* pose_b, const Pose2& T_a_b);

/// e^T Omega e for the given blocks.
double Se2Chi2(const double* pose_a, const double* pose_b, const Pose2& T_a_b,
               const Eigen::Matrix3d& sqrt_information);

class Se2EdgeCost final : public ceres::SizedCostFunction<3, 3, 3> {
 public:
  Se2EdgeCost(const Pose2& T_a_b, const Eigen::Matrix3d& sqrt_information)
      : T_a_b_(T_a_b), sqrt_information_(sqrt_information) {}

  bool Evaluate(double const* const* parameters, double* residuals,
                double** jacobians) const override;

 private:
  Pose2 T_a_b_;
  Eigen::Matrix3d sqrt_information_;
};

}  // namespace uwbsar
