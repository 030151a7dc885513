#include "backend/odometry_calibration.h"

namespace uwbsar {

Pose2 CorrectedOdometryStep(const OdometryCalibration& calibration, const Pose2& measured,
                            const OdometryTravel& travel, double gyro_bias_radps) {
  double c[3];
  CorrectOdometryStep(calibration.data(), gyro_bias_radps, measured, travel, c);
  return {c[0], c[1], c[2]};
}

ceres::CostFunction* CalibratedOdometryCost::Create(const Pose2& T_a_b,
                                                    const OdometryTravel& travel,
                                                    const Eigen::Matrix3d& sqrt_information) {
  return new ceres::AutoDiffCostFunction<CalibratedOdometryCost, 3, 3, 3, 3, 1>(
      new CalibratedOdometryCost(T_a_b, travel, sqrt_information));
}

double CalibratedOdometryChi2(const double* pose_a, const double* pose_b,
                              const OdometryCalibration& calibration, const Pose2& T_a_b,
                              const OdometryTravel& travel, const Eigen::Matrix3d& sqrt_information,
                              double gyro_bias_radps) {
  const CalibratedOdometryCost cost(T_a_b, travel, sqrt_information);
  double r[3];
  cost(pose_a, pose_b, calibration.data(), &gyro_bias_radps, r);
  return r[0] * r[0] + r[1] * r[1] + r[2] * r[2];
}

bool OdometryCalibrationPrior::Evaluate(double const* const* parameters, double* residuals,
                                        double** jacobians) const {
  for (int i = 0; i < 3; ++i) residuals[i] = (parameters[0][i] - mean_[i]) / sigma_[i];
  if (jacobians != nullptr && jacobians[0] != nullptr) {
    for (int i = 0; i < 9; ++i) jacobians[0][i] = 0.0;
    for (int i = 0; i < 3; ++i) jacobians[0][i * 3 + i] = 1.0 / sigma_[i];
  }
  return true;
}

double OdometryCalibrationPrior::Chi2(const OdometryCalibration& calibration) const {
  double sum = 0.0;
  for (int i = 0; i < 3; ++i) {
    const double r = (calibration[i] - mean_[i]) / sigma_[i];
    sum += r * r;
  }
  return sum;
}

}  // namespace uwbsar
