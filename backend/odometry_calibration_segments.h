// The segments calibrate's fit compares (backend/odometry_calibration_fit.h): the run cut into
// stretches of about CalibrationFitOptions::segment_m of odometry path (or 1 rad of turn), each
// holding the odometry's increments and the ground truth's step over it, and the cost that
// compares the two once the calibration (and a gyro's bias) corrects the odometry.
#pragma once

#include <Eigen/Core>
#include <cmath>
#include <vector>

#include "backend/backend_config.h"
#include "backend/odometry_calibration.h"
#include "backend/odometry_calibration_fit.h"
#include "core/types.h"

namespace uwbsar {
namespace calibration_fit {

/// One segment: the odometry's increments with their travel, and the truth's step.
struct Segment {
  std::vector<Pose2> increments;        ///< odometry sample to sample, in the robot's frame
  std::vector<OdometryTravel> travels;  ///< with each increment's duration (a gyro's bias)
  Pose2 truth;
  double path_m = 0.0;
  double turn_rad = 0.0;
  double duration_s = 0.0;
  double middle_s = 0.0;  ///< its middle's time after the first odometry sample
};

/// The segment's odometry, each increment corrected by the calibration and the gyro bias
/// (CorrectOdometryStep, the backend's model applied at the odometry's own rate) and composed;
/// the residual is its SE(2) error against the truth, whitened like an odometry edge of that
/// path. Without a bias block (a wheel base) the bias is 0.
class SegmentCost {
 public:
  SegmentCost(const Segment* segment, const Eigen::Matrix3d& sqrt_information)
      : segment_(segment), sqrt_information_(sqrt_information) {}

  template <typename T>
  bool operator()(const T* calibration, T* residuals) const {
    const T no_bias(0.0);
    return operator()(calibration, &no_bias, residuals);
  }

  template <typename T>
  bool operator()(const T* calibration, const T* gyro_bias, T* residuals) const {
    using std::cos;
    using std::sin;
    T x(0.0), y(0.0), yaw(0.0);
    for (std::size_t i = 0; i < segment_->increments.size(); ++i) {
      T step[3];
      CorrectOdometryStep(calibration, gyro_bias[0], segment_->increments[i], segment_->travels[i],
                          step);
      x += cos(yaw) * step[0] - sin(yaw) * step[1];
      y += sin(yaw) * step[0] + cos(yaw) * step[1];
      yaw += step[2];
    }
    const Pose2& t = segment_->truth;
    const double c = std::cos(t.yaw_rad), s = std::sin(t.yaw_rad);
    const T dx = x - t.x_m, dy = y - t.y_m;
    // A segment turns less than 1 rad (CutSegments): the yaw difference needs no wrapping.
    const T e[3] = {c * dx + s * dy, -s * dx + c * dy, yaw - t.yaw_rad};
    for (int r = 0; r < 3; ++r) {
      residuals[r] = sqrt_information_(r, 0) * e[0] + sqrt_information_(r, 1) * e[1] +
                     sqrt_information_(r, 2) * e[2];
    }
    return true;
  }

 private:
  const Segment* segment_;
  Eigen::Matrix3d sqrt_information_;
};

/// The run cut into segments (the file comment) where the ground truth (interpolated at the
/// odometry's stamps) is within options.max_truth_gap_s on both sides; a gap restarts them.
std::vector<Segment> CutSegments(const std::vector<OdometrySample>& odometry,
                                 const std::vector<OdometrySample>& ground_truth,
                                 const CalibrationFitOptions& options);

/// A segment's residual weight: an odometry edge's information over its path.
Eigen::Matrix3d SegmentSqrtInformation(const Segment& s, const BackendConfig& config);

/// Position and heading error of the segments' odometry corrected by `c` and `bias[i]` (one
/// per segment, rad/s), rms.
void SegmentErrors(const std::vector<Segment>& segments, const OdometryCalibration& c,
                   const std::vector<double>& bias, double* xy_rms_m, double* yaw_rms_rad);

}  // namespace calibration_fit
}  // namespace uwbsar
