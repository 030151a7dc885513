#include "backend/edge_composition.h"

#include <Eigen/LU>
#include <cmath>

namespace uwbsar {
namespace {

Eigen::Matrix2d Rotation(double yaw_rad) {
  const double c = std::cos(yaw_rad), s = std::sin(yaw_rad);
  Eigen::Matrix2d r;
  r << c, -s, s, c;
  return r;
}

}  // namespace

RelativePose InvertRelativePose(const RelativePose& ab) {
  // t_ba = -R_ab^T t_ab, yaw_ba = -yaw_ab.
  const Eigen::Matrix2d Rt = Rotation(ab.T_a_b.yaw_rad).transpose();
  const Eigen::Vector2d t(ab.T_a_b.x_m, ab.T_a_b.y_m);
  Eigen::Matrix3d J = Eigen::Matrix3d::Zero();
  J.topLeftCorner<2, 2>() = -Rt;
  J.topRightCorner<2, 1>() = Rt * Eigen::Vector2d(-t.y(), t.x());  // d(-R^T t)/d yaw
  J(2, 2) = -1.0;
  return {ab.T_a_b.Inverse(), J * ab.covariance * J.transpose()};
}

RelativePose ComposeRelativePoses(const RelativePose& ab, const RelativePose& bc) {
  // t_ac = t_ab + R_ab t_bc, yaw_ac = yaw_ab + yaw_bc.
  const Eigen::Matrix2d R = Rotation(ab.T_a_b.yaw_rad);
  const Eigen::Vector2d rt = R * Eigen::Vector2d(bc.T_a_b.x_m, bc.T_a_b.y_m);
  Eigen::Matrix3d J1 = Eigen::Matrix3d::Identity();
  J1(0, 2) = -rt.y();
  J1(1, 2) = rt.x();
  Eigen::Matrix3d J2 = Eigen::Matrix3d::Identity();
  J2.topLeftCorner<2, 2>() = R;
  const Eigen::Matrix3d cov =
      J1 * ab.covariance * J1.transpose() + J2 * bc.covariance * J2.transpose();
  return {ab.T_a_b * bc.T_a_b, 0.5 * (cov + cov.transpose())};
}

RelativePose FuseRelativePoses(const RelativePose& x, const RelativePose& y) {
  const Eigen::Matrix3d ix = x.covariance.inverse(), iy = y.covariance.inverse();
  const Eigen::Matrix3d info = ix + iy;
  const Eigen::Matrix3d cov = info.inverse();
  const Eigen::Vector3d zx(x.T_a_b.x_m, x.T_a_b.y_m, x.T_a_b.yaw_rad);
  const Eigen::Vector3d zy(y.T_a_b.x_m, y.T_a_b.y_m,
                           x.T_a_b.yaw_rad + NormalizeAngle(y.T_a_b.yaw_rad - x.T_a_b.yaw_rad));
  const Eigen::Vector3d z = cov * (ix * zx + iy * zy);
  return {Pose2{z.x(), z.y(), NormalizeAngle(z.z())}, 0.5 * (cov + cov.transpose())};
}

}  // namespace uwbsar
