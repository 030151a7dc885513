// Online odometry calibration: a few intrinsics of a trajectory's wheel odometry, estimated
// as one extra Ceres parameter block shared by all of that trajectory's odometry edges.
// The block is [scale, heading_drift_rad_per_m, rotation_scale]; a measured odometry step
// T_a_b = (x, y, yaw) over a travelled path of d metres and a time of dt seconds during which
// the robot turned by theta (OdometryTravel) is corrected to
//   yaw_c = yaw + rotation_scale * theta - heading_drift_rad_per_m * d - gyro_bias_radps * dt
//   t_c   = (1 + scale) * R((yaw_c - yaw) / 2) * (x, y)
// (the heading change moves the chord's direction by half of it, as in the base's midpoint
// integration), and the residual is the SE(2) residual of backend/se2_edge_cost.h with T_c
// as the measurement. This models a differential drive: a wrong mean wheel radius (scale),
// unequal wheel radii (a heading drift per metre of straight travel) and a wrong wheelbase
// (turns under- or over-reported). All zero is the uncalibrated odometry.
// A base whose heading comes from a gyro (backend.odometry_model: gyro, the Kobuki's default)
// errs differently: its turns' scale belongs to the robot, but its heading error is the gyro's
// bias, set at each power-up and wandering, integrated over time. That bias is a state of the
// run (backend/gyro_bias_track.h), not of the robot: the heading drift per metre is held at 0
// and each step is corrected by the bias in effect over it times its duration.
// For nodes in the robot's frame, d = |(x, y)| and theta = yaw (the defaults). For nodes
// whose frames keep the odometry's world orientation (the keyframe tiles' anchors, whose
// steps have yaw 0), theta is the robot's own turn between the two and d its path: the
// node's yaw is then the rotation of the odometry's world frame, which the drift and the
// turns' error change between the two.
//
// The block gets a prior (OdometryCalibrationPrior): weak and at zero for an uncalibrated base,
// at the base's measured calibration when it has one. It is only left free while loops
// constrain its trajectory (backend/pose_graph.h); without loops nothing observes it, and the
// odometry is corrected by the prior's mean. Nothing on a tour observes the distance scale (a
// ring scaled by any factor still closes, and every loop is a short relative measurement), so
// the map's scale is the mean's: a base over-reporting its travel by 0.5 % scales the map by
// 0.5 % unless its calibration is given.
#pragma once

#include <ceres/ceres.h>

#include <Eigen/Core>
#include <array>
#include <cmath>

#include "core/pose2.h"

namespace uwbsar {

/// Indices into the calibration parameter block.
enum OdometryCalibrationIndex : int { kCalibScale = 0, kCalibHeadingDrift = 1, kCalibRotation = 2 };
using OdometryCalibration = std::array<double, 3>;

/// The robot's own motion over an odometry step: its path and its turn.
struct OdometryTravel {
  double path_m = 0.0;
  double turn_rad = 0.0;
  double duration_s = 0.0;  ///< the step's time (gyro bias); 0: unknown, no bias applies
};

/// The travel of a step between nodes in the robot's frame: |t| and its yaw.
inline OdometryTravel TravelOf(const Pose2& T_a_b) {
  return {std::hypot(T_a_b.x_m, T_a_b.y_m), T_a_b.yaw_rad};
}

/// The travel of a step: `path_m` and `turn_rad` where given (path_m >= 0, turn_rad finite),
/// else TravelOf(T_a_b)'s.
inline OdometryTravel TravelOf(const Pose2& T_a_b, double path_m, double turn_rad) {
  OdometryTravel travel = TravelOf(T_a_b);
  if (path_m >= 0) travel.path_m = path_m;
  if (std::isfinite(turn_rad)) travel.turn_rad = turn_rad;
  return travel;
}

/// T_c of the file comment, generic over Ceres jets. `corrected` is (x_m, y_m, yaw_rad).
template <typename T>
void CorrectOdometryStep(const T* calibration, const T& gyro_bias_radps, const Pose2& measured,
                         const OdometryTravel& travel, T* corrected) {
  using std::cos;
  using std::sin;
  const T yaw_c = measured.yaw_rad + calibration[kCalibRotation] * travel.turn_rad -
                  calibration[kCalibHeadingDrift] * travel.path_m -
                  gyro_bias_radps * travel.duration_s;
  const T half_turn = 0.5 * (yaw_c - measured.yaw_rad);
  const T c = cos(half_turn), s = sin(half_turn);
  const T k = T(1.0) + calibration[kCalibScale];
  corrected[0] = k * (c * measured.x_m - s * measured.y_m);
  corrected[1] = k * (s * measured.x_m + c * measured.y_m);
  corrected[2] = yaw_c;
}

/// The same without a gyro bias (a wheel-only base, or a step of unknown duration).
template <typename T>
void CorrectOdometryStep(const T* calibration, const Pose2& measured, const OdometryTravel& travel,
                         T* corrected) {
  CorrectOdometryStep(calibration, T(0.0), measured, travel, corrected);
}

/// The corrected step as a pose (for tests and reports).
Pose2 CorrectedOdometryStep(const OdometryCalibration& calibration, const Pose2& measured,
                            const OdometryTravel& travel, double gyro_bias_radps = 0.0);
inline Pose2 CorrectedOdometryStep(const OdometryCalibration& calibration, const Pose2& measured) {
  return CorrectedOdometryStep(calibration, measured, TravelOf(measured));
}

/// Residual of an odometry edge with calibration: blocks pose a, pose b (3 each, as in
/// se2_edge_cost.h), the calibration (3) and the gyro bias over the step (1, rad/s). |r|^2 is
/// the edge's chi2.
class CalibratedOdometryCost {
 public:
  CalibratedOdometryCost(const Pose2& T_a_b, const OdometryTravel& travel,
                         const Eigen::Matrix3d& sqrt_information)
      : T_a_b_(T_a_b), travel_(travel), sqrt_information_(sqrt_information) {}

  template <typename T>
  bool operator()(const T* a, const T* b, const T* calibration, const T* gyro_bias,
                  T* residuals) const {
    using std::atan2;
    using std::cos;
    using std::sin;
    T m[3];
    CorrectOdometryStep(calibration, gyro_bias[0], T_a_b_, travel_, m);
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
  static ceres::CostFunction* Create(const Pose2& T_a_b, const OdometryTravel& travel,
                                     const Eigen::Matrix3d& sqrt_information);

 private:
  Pose2 T_a_b_;
  OdometryTravel travel_;
  Eigen::Matrix3d sqrt_information_;
};

/// e^T Omega e of a calibrated odometry edge.
double CalibratedOdometryChi2(const double* pose_a, const double* pose_b,
                              const OdometryCalibration& calibration, const Pose2& T_a_b,
                              const OdometryTravel& travel, const Eigen::Matrix3d& sqrt_information,
                              double gyro_bias_radps = 0.0);

/// The prior: r_i = (calibration_i - mean_i) / sigma_i. The mean is the base's calibration as
/// measured once (backend.calibration_*_mean; zero for an uncalibrated base), sigma how far
/// the estimate may move from it.
class OdometryCalibrationPrior final : public ceres::SizedCostFunction<3, 3> {
 public:
  OdometryCalibrationPrior(const OdometryCalibration& mean, const Eigen::Vector3d& sigma)
      : mean_(mean), sigma_(sigma) {}
  bool Evaluate(double const* const* parameters, double* residuals,
                double** jacobians) const override;
  /// |r|^2 at the given calibration.
  double Chi2(const OdometryCalibration& calibration) const;
  const OdometryCalibration& mean() const { return mean_; }

 private:
  OdometryCalibration mean_;
  Eigen::Vector3d sigma_;
};

}  // namespace uwbsar
