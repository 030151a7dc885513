// The Ceres residual of the right-angle prior between two wall landmarks (buildings are mostly
// rectilinear): their normals differ by a whole number of quarter turns. A functor with automatic
// derivatives that can be evaluated and tested on its own.
#pragma once

#include <ceres/autodiff_cost_function.h>

#include <cmath>

namespace uwbsar {

/// Residual (a_normal - b_normal - quarter_turns x pi/2, wrapped to (-pi, pi]) / std_rad;
/// parameters: the two landmarks' blocks [normal_rad, offset_m]. quarter_turns is chosen once,
/// when the prior is made (the nearest to the two lines' angle then), so the residual is smooth.
class LineRightAngleCost {
 public:
  LineRightAngleCost(int quarter_turns, double std_rad)
      : target_rad_(quarter_turns * 0.5 * M_PI), std_rad_(std_rad) {}

  template <typename T>
  bool operator()(const T* a, const T* b, T* residual) const {
    using std::floor;
    T d = a[0] - b[0] - target_rad_;
    const double two_pi = 2.0 * M_PI;
    d = d - two_pi * floor((d + M_PI) / two_pi);
    residual[0] = d / std_rad_;
    return true;
  }

  static ceres::CostFunction* Create(int quarter_turns, double std_rad) {
    return new ceres::AutoDiffCostFunction<LineRightAngleCost, 1, 2, 2>(
        new LineRightAngleCost(quarter_turns, std_rad));
  }

 private:
  double target_rad_;
  double std_rad_;
};

}  // namespace uwbsar
