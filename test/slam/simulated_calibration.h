// Test helper: the fit `uwbsar calibrate` makes of a simulated run, its odometry as the SLAM
// system received it against the simulator's ground truth (for the tour tests' calibrated bases),
// and a configuration with that calibration applied as its file is.
#pragma once

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

#include "app/app_config_io.h"
#include "backend/odometry_calibration_fit.h"
#include "slam/jobs/calibrate_job.h"
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

/// `config` with the base's odometry calibration measured as `uwbsar calibrate` does, on another
/// map's run with ground truth (seed_hall's 15 m loop, seed 7), and applied as its file is:
/// only the robot's keys (a gyro base's bias belongs to the run and is not written).
inline Config CalibratedBase(Config config) {
  const slam::MapRun calibration_run = slam::MapSimulation(
      config, std::string(UWBSAR_SOURCE_DIR) + "/config/maps/seed_hall/seed_hall.yaml", "loop",
      /*seed=*/7);
  const CalibrationFit fit = FitSimulatedRun(calibration_run, config.backend);
  const double true_scale = 1.0 / (1.0 + config.simulator.odometry.wheel_scale_error) - 1.0;
  std::printf(
      "calibration: %s base, scale %.5f +- %.5f (truth %.5f), drift %.5f, rotation %.4f; run's "
      "gyro bias %.4f deg/s\n",
      EnumName(fit.model), fit.calibration[kCalibScale], fit.sigma[kCalibScale], true_scale,
      fit.calibration[kCalibHeadingDrift], fit.calibration[kCalibRotation],
      fit.gyro_bias_mean_radps * 180 / M_PI);
  EXPECT_NEAR(fit.calibration[kCalibScale], true_scale, 0.001);
  EXPECT_EQ(fit.model, config.backend.odometry_model);  // the simulated base's kind, detected
  // The file `uwbsar calibrate --out` writes, given after the robot's configuration: its keys
  // replace the defaults' (`config`'s backend is the defaults').
  config.backend = LoadConfigFromString(slam::CalibrationYaml(fit), "calibration.yaml").backend;
  return config;
}

}  // namespace uwbsar::testing
