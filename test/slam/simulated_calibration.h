// Test helper: the fit `uwbsar calibrate` makes of a simulated run, its odometry as the SLAM
// system received it against the simulator's ground truth (for the tour tests' calibrated bases).
#pragma once

#include <vector>

#include "backend/odometry_calibration_fit.h"
#include "slam/map_job.h"
#include "slam/slam_system.h"

namespace uwbsar::testing {

inline CalibrationFit FitSimulatedRun(const slam::MapRun& run, const BackendConfig& backend) {
  std::vector<OdometrySample> odometry;
  for (const OdometryEntry& e : run.slam->odometry()) {
    OdometrySample o;
    o.stamp_ns = e.stamp_ns;
    o.T_world_robot = e.T_world_robot;
    odometry.push_back(o);
  }
  return FitOdometryCalibration(odometry, run.ground_truth, backend);
}

}  // namespace uwbsar::testing
