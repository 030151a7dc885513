// Private to the pose graph (backend/pose_graph*.cc): the solver-side records behind
// PoseGraph, shared by its translation units. Not part of the backend's interface.
#pragma once

#include <ceres/loss_function.h>
#include <ceres/problem.h>

#include <array>
#include <memory>

#include "backend/gyro_bias_track.h"
#include "backend/odometry_calibration.h"
#include "backend/pose_graph.h"
#include "backend/se2_edge_cost.h"

namespace uwbsar {

/// The configured robust loss of loops, wall edges and landmark observations (a new object,
/// for the caller to own); nullptr for "none".
inline ceres::LossFunction* MakeRobustLoss(const BackendConfig& c) {
  if (c.robust_loss == RobustLoss::kCauchy) return new ceres::CauchyLoss(c.robust_loss_scale);
  if (c.robust_loss == RobustLoss::kHuber) return new ceres::HuberLoss(c.robust_loss_scale);
  return nullptr;  // "none": plain least squares
}

struct PoseGraph::SolverNode {
  // The Ceres parameter block [x_m, y_m, yaw_rad] in the solver frame: the world frame
  // moved to the first node's initial position (see solver_origin_).
  std::array<double, 3> x{};
};

/// One trajectory's odometry intrinsics (backend/odometry_calibration.h): a parameter block
/// shared by the trajectory's odometry edges, constant at zero while no loop constrains it.
struct PoseGraph::CalibrationBlock {
  OdometryCalibration x{};
  const OdometryCalibrationPrior* prior = nullptr;  // owned by the problem
  bool free = false;
};

struct PoseGraph::SolverEdge {
  int index = 0;
  PoseGraphEdge edge;
  Eigen::Matrix3d sqrt_information;
  SolverNode* from = nullptr;
  SolverNode* to = nullptr;
  ceres::ResidualBlockId residual = nullptr;  // in the problem (RemoveNode takes it out)
  CalibrationBlock* calibration = nullptr;    // calibrated odometry edges only
  double* gyro_bias = nullptr;                // their gyro bias block (rad/s)
  OdometryTravel travel;                      // the robot's path, turn and time (calibrated)
  // Loops only: the loss is swapped between robust, none and "switched off" without
  // touching the problem's structure (the wrapper is owned here, not by the problem).
  std::unique_ptr<ceres::LossFunctionWrapper> loss;
  bool rejected = false;
  bool held_back = false;       // unsupported and not (yet) confirmed by the solution
  bool inconsistent = false;    // blamed for an odometry edge out of its noise: stays rejected
  bool trialled = false;        // held back and tried once in a solve of its own
  bool trial_accepted = false;  // that trial kept the map consistent: no longer held back
  int support = -1;
  double chi2 = 0.0;

  /// The measurement as the current calibration and gyro bias correct it.
  Pose2 CorrectedMeasurement() const {
    return calibration != nullptr
               ? CorrectedOdometryStep(calibration->x, edge.T_from_to, travel, *gyro_bias)
               : edge.T_from_to;
  }

  double Chi2() const {
    if (calibration != nullptr) {
      return CalibratedOdometryChi2(from->x.data(), to->x.data(), calibration->x, edge.T_from_to,
                                    travel, sqrt_information, *gyro_bias);
    }
    return Se2Chi2(from->x.data(), to->x.data(), edge.T_from_to, sqrt_information);
  }
};

/// A line landmark's block [normal_rad, offset_m] in the solver frame (backend/line_landmark.h).
struct PoseGraph::SolverLandmark {
  std::array<double, 2> x{};
  bool fixed = false;  ///< held constant (a saved map's wall): never re-seeded
};

struct PoseGraph::SolverObservation {
  int index = 0;
  LineObservation observation;
  SolverNode* node = nullptr;
  SolverLandmark* landmark = nullptr;
  ceres::ResidualBlockId residual = nullptr;
  std::unique_ptr<ceres::LossFunctionWrapper> loss;  // robust, or zero weight once rejected
  bool rejected = false;
  double chi2 = 0.0;

  double Chi2() const {
    return LineObservationChi2(observation, Pose2{node->x[0], node->x[1], node->x[2]},
                               Line2{landmark->x[0], landmark->x[1]});
  }
};

}  // namespace uwbsar
