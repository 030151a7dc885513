#include "backend/se2_edge_cost.h"

#include <Eigen/Cholesky>
#include <cmath>

namespace uwbsar {

std::optional<Eigen::Matrix3d> SqrtInformation(const Eigen::Matrix3d& information) {
  if (!information.allFinite()) return std::nullopt;
  const double scale = information.cwiseAbs().maxCoeff();
  if (!(scale > 0.0)) return std::nullopt;
  if ((information - information.transpose()).cwiseAbs().maxCoeff() > 1e-9 * scale) {
    return std::nullopt;
  }
  const Eigen::LLT<Eigen::Matrix3d> llt(information);
  if (llt.info() != Eigen::Success) return std::nullopt;
  const Eigen::Matrix3d upper = llt.matrixU();
  // LLT succeeds on matrices that are positive definite only up to round-off; demand a
  // meaningful smallest pivot so that a singular information is rejected, not inverted.
  if (upper.diagonal().minCoeff() <= 1e-9 * std::sqrt(scale)) return std::nullopt;
  return upper;
}

Eigen::Vector3d Se2Error(const double* a, const double* b, const Pose2& T_a_b) {
  const double c = std::cos(a[2]), s = std::sin(a[2]);
  const double dx = b[0] - a[0], dy = b[1] - a[1];
  return {c * dx + s * dy - T_a_b.x_m, -s * dx + c * dy - T_a_b.y_m,
          NormalizeAngle(b[2] - a[2] - T_a_b.yaw_rad)};
}

double Se2Chi2(const double* a, const double* b, const Pose2& T_a_b,
               const Eigen::Matrix3d& sqrt_information) {
  return (sqrt_information * Se2Error(a, b, T_a_b)).squaredNorm();
}

bool Se2EdgeCost::Evaluate(double const* const* parameters, double* residuals,
                           double** jacobians) const {
  const double* a = parameters[0];
  const double* b = parameters[1];
  const double c = std::cos(a[2]), s = std::sin(a[2]);
  const double dx = b[0] - a[0], dy = b[1] - a[1];
  const Eigen::Vector3d e(c * dx + s * dy - T_a_b_.x_m, -s * dx + c * dy - T_a_b_.y_m,
                          NormalizeAngle(b[2] - a[2] - T_a_b_.yaw_rad));
  Eigen::Map<Eigen::Vector3d> r(residuals);
  r = sqrt_information_ * e;
  if (jacobians == nullptr) return true;
  using RowMajor3 = Eigen::Matrix<double, 3, 3, Eigen::RowMajor>;
  if (jacobians[0] != nullptr) {
    Eigen::Matrix3d de_da;
    de_da << -c, -s, -s * dx + c * dy,  //
        s, -c, -c * dx - s * dy,        //
        0.0, 0.0, -1.0;
    Eigen::Map<RowMajor3> j(jacobians[0]);
    j = sqrt_information_ * de_da;
  }
  if (jacobians[1] != nullptr) {
    Eigen::Matrix3d de_db;
    de_db << c, s, 0.0,  //
        -s, c, 0.0,      //
        0.0, 0.0, 1.0;
    Eigen::Map<RowMajor3> j(jacobians[1]);
    j = sqrt_information_ * de_db;
  }
  return true;
}

}  // namespace uwbsar
