// The Ceres residual of one wall landmark observation (the model in backend/line_landmark.h),
// with automatic derivatives; a functor that can be evaluated and tested on its own.
#pragma once

#include <ceres/autodiff_cost_function.h>

#include <cmath>

#include "backend/line_landmark.h"

namespace uwbsar {

/// The residual functor of one observation (see the file comment); parameters: the node's
/// pose block [x_m, y_m, yaw_rad] and the landmark's block [normal_rad, offset_m], both in the
/// same (solver) frame.
class LineObservationCost {
 public:
  explicit LineObservationCost(const LineObservation& observation) : obs_(observation) {}

  template <typename T>
  bool operator()(const T* pose, const T* landmark, T* residual) const {
    using std::cos;
    using std::floor;
    using std::sin;
    const T a_n = landmark[0] - pose[2];
    const T d_n = landmark[1] - (cos(landmark[0]) * pose[0] + sin(landmark[0]) * pose[1]);
    const double qx = obs_.reference_node.x_m, qy = obs_.reference_node.y_m;
    const double a_obs = obs_.line_node.normal_rad;
    const double at_q_obs = obs_.line_node.offset_m - (std::cos(a_obs) * qx + std::sin(a_obs) * qy);
    const T at_q = d_n - (cos(a_n) * qx + sin(a_n) * qy);
    T da = a_n - a_obs;
    // wrap to (-pi, pi]: the landmark block is not wrapped, only the residual
    const double two_pi = 2.0 * M_PI;
    da = da - two_pi * floor((da + M_PI) / two_pi);
    residual[0] = (at_q - at_q_obs) / obs_.offset_std_m;
    residual[1] = da / obs_.normal_std_rad;
    return true;
  }

  static ceres::CostFunction* Create(const LineObservation& observation) {
    return new ceres::AutoDiffCostFunction<LineObservationCost, 2, 3, 2>(
        new LineObservationCost(observation));
  }

 private:
  LineObservation obs_;
};

}  // namespace uwbsar
