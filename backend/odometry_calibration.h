// Online odometry calibration: a few intrinsics of a trajectory's wheel odometry, estimated
// as one extra Ceres parameter block shared by all of that trajectory's odometry edges.
// The block is [scale, heading_drift_rad_per_m, rotation_scale]; a measured odometry step
// T_a_b = (x, y, yaw) over the travelled distance d = |(x, y)| is corrected to
//   yaw_c = yaw * (1 + rotation_scale) - heading_drift_rad_per_m * d
//   t_c   = (1 + scale) * R((yaw_c - yaw) / 2) * (x, y)
// (the heading change moves the chord's direction by half of it, as in the base's midpoint
// integration), and the residual is the SE(2) residual of backend/se2_edge_cost.h with T_c
// as the measurement. This models a differential drive: a wrong mean wheel radius (scale),
// unequal wheel radii (a heading drift per metre of straight travel) and a wrong wheelbase
// (turns under- or over-reported). All zero is the uncalibrated odometry.
//
// The block gets a weak prior at zero (OdometryCalibrationPrior) and is only left free while
// loops constrain its trajectory (backend/pose_graph.h); without loops nothing observes it.
#pragma once

#include <ceres/ceres.h>

#include <Eigen/Core>
#include <array>
#include <cmath>

#include "slam/pose2.h"

namespace uwbsar {

/// Indices into the calibration parameter block.
enum OdometryCalibrationIndex : int { kCalibScale = 0, kCalibHeadingDrift = 1, kCalibRotation = 2 };
using OdometryCalibration = std::array<double, 3>;

/// T_c of the file comment, generic over Ceres jets. `corrected` is (x_m, y_m, yaw_rad).
template <typename T>
void CorrectOdometryStep(const T* calibration, const Pose2& measured, T* corrected) {
  using std::cos;
  using std::sin;
  const double d = std::hypot(measured.x_m, measured.y_m);
  const T yaw_c = measured.yaw_rad * (T(1.0) + calibration[kCalibRotation]) -
                  calibration[kCalibHeadingDrift] * d;
  const T half_turn = 0.5 * (yaw_c - measured.yaw_rad);
  const T c = cos(half_turn), s = sin(half_turn);
  const T k = T(1.0) + calibration[kCalibScale];
  corrected[0] = k * (c * measured.x_m - s * measured.y_m);
  corrected[1] = k * (s * measured.x_m + c * measured.y_m);
  corrected[2] = yaw_c;
}

/// The corrected step as a pose (for tests and reports).
Pose2 CorrectedOdometryStep(const OdometryCalibration& calibration, const Pose2& measured);

/// Residual of an odometry edge with calibration: blocks pose a, pose b (3 each, as in
/// se2_edge_cost.h) and the calibration (3). |r|^2 is the edge's chi2.
class CalibratedOdometryCost {
 public:
  CalibratedOdometryCost(const Pose2& T_a_b, const Eigen::Matrix3d& sqrt_information)
      : T_a_b_(T_a_b), sqrt_information_(sqrt_information) {}

  template <typename T>
  bool operator()(const T* a, const T* b, const T* calibration, T* residuals) const {
    using std::atan2;
    using std::cos;
    using std::sin;
    T m[3];
    CorrectOdometryStep(calibration, T_a_b_, m);
    const T c = cos(a[2]), s = sin(a[2]);
    const T dx = b[0] - a[0], dy = b[1] - a[1];
    const T dyaw = b[2] - a[2] - m[2];
    const T e[3] = {c * dx + s * dy - m[0], -s * dx + c * dy - m[1], atan2(sin(dyaw), cos(dyaw))};
    for (int i = 0; i < 3; ++i) {
      residuals[i] = sqrt_information_(i, 0) * e[0] + sqrt_information_(i, 1) * e[1] +
                     sqrt_information_(i, 2) * e[2];
    }
    return true;
  }

  /// A Ceres cost function (owned by the caller or the problem).
  static ceres::CostFunction* Create(const Pose2& T_a_b, const Eigen::Matrix3d& sqrt_information);

 private:
  Pose2 T_a_b_;
  Eigen::Matrix3d sqrt_information_;
};

/// e^T Omega e of a calibrated odometry edge.
double CalibratedOdometryChi2(const double* pose_a, const double* pose_b,
                              const OdometryCalibration& calibration, const Pose2& T_a_b,
                              const Eigen::Matrix3d& sqrt_information);

/// The weak prior at zero: r_i = calibration_i / sigma_i.
class OdometryCalibrationPrior final : public ceres::SizedCostFunction<3, 3> {
 public:
  explicit OdometryCalibrationPrior(const Eigen::Vector3d& sigma) : sigma_(sigma) {}
  bool Evaluate(double const* const* parameters, double* residuals,
                double** jacobians) const override;
  /// |r|^2 at the given calibration.
  double Chi2(const OdometryCalibration& calibration) const;

 private:
  Eigen::Vector3d sigma_;
};

}  // namespace uwbsar
