// The configuration file `uwbsar calibrate` writes: the fit's backend keys that belong to the
// robot through the configuration writer, loadable by --config, and nothing else (never a
// gyro's bias, which belongs to the run).
#include "slam/jobs/calibrate_job.h"

#include <gtest/gtest.h>

#include "app/app_config_io.h"

namespace uwbsar::slam {
namespace {

CalibrationFit SomeFit(bool scale_observed) {
  CalibrationFit fit;
  fit.model = OdometryModel::kWheel;
  fit.calibration[kCalibScale] = -0.00497512;
  fit.calibration[kCalibHeadingDrift] = 0.0011;
  fit.calibration[kCalibRotation] = 0.0123456789;
  fit.sigma = {0.0004, 0.0002, 0.003};
  fit.observed = {scale_observed, false, true};
  fit.segments = 24;
  fit.path_m = 14.75;
  return fit;
}

TEST(CalibrateJobTest, CalibrationYamlIsTheFitsBackendKeysInTheFilesOrder) {
  EXPECT_EQ(CalibrationYaml(SomeFit(true)),
            "# uwbsar calibrate: 24 segments, 14.75 m, wheel base\n"
            "backend:\n"
            "  odometry_model: wheel\n"
            "  calibration_scale_sigma: 0.0012\n"
            "  calibration_scale_mean: -0.00497512\n"
            "  calibration_heading_drift_mean_rad_per_m: 0.0011\n"
            "  calibration_rotation_mean: 0.0123457\n");
}

TEST(CalibrateJobTest, CalibrationYamlLoadsAsTheFitAndDefaultsElsewhere) {
  for (const bool observed : {true, false}) {
    const std::string yaml = CalibrationYaml(SomeFit(observed));
    Config loaded = LoadConfigFromString(yaml, "calibration.yaml");
    EXPECT_DOUBLE_EQ(loaded.backend.calibration_scale_mean, -0.00497512);
    EXPECT_DOUBLE_EQ(loaded.backend.calibration_heading_drift_mean_rad_per_m, 0.0011);
    EXPECT_DOUBLE_EQ(loaded.backend.calibration_rotation_mean, 0.0123457);
    // The scale's sigma: 3 x the fit's, at least 0.001; the configured one when unobserved.
    EXPECT_DOUBLE_EQ(loaded.backend.calibration_scale_sigma,
                     observed ? 0.0012 : BackendConfig{}.calibration_scale_sigma);
    EXPECT_EQ(yaml.find("calibration_scale_sigma") != std::string::npos, observed) << yaml;
    // Nothing else: every other key keeps its default.
    EXPECT_EQ(loaded.backend.odometry_model, OdometryModel::kWheel);
    const BackendConfig defaults;
    loaded.backend.odometry_model = defaults.odometry_model;
    loaded.backend.calibration_scale_mean = defaults.calibration_scale_mean;
    loaded.backend.calibration_heading_drift_mean_rad_per_m =
        defaults.calibration_heading_drift_mean_rad_per_m;
    loaded.backend.calibration_rotation_mean = defaults.calibration_rotation_mean;
    loaded.backend.calibration_scale_sigma = defaults.calibration_scale_sigma;
    EXPECT_EQ(ConfigToYaml(loaded), ConfigToYaml(Config{}));
  }
}

// Issue 44: a gyro base's file holds its scales and its kind, not the run's bias, and no drift
// per metre (which the configuration refuses with odometry_model gyro).
TEST(CalibrateJobTest, AGyroBasesFileHoldsItsScalesAndKindButNotTheRunsBias) {
  CalibrationFit fit = SomeFit(true);
  fit.model = OdometryModel::kGyro;
  fit.calibration[kCalibHeadingDrift] = 0.0;
  fit.gyro_bias_mean_radps = 0.0007;
  fit.gyro_bias_segments = {{0.0, 0.0007}};
  const std::string yaml = CalibrationYaml(fit);
  EXPECT_EQ(yaml,
            "# uwbsar calibrate: 24 segments, 14.75 m, gyro base\n"
            "backend:\n"
            "  odometry_model: gyro\n"
            "  calibration_scale_sigma: 0.0012\n"
            "  calibration_scale_mean: -0.00497512\n"
            "  calibration_rotation_mean: 0.0123457\n");
  Config loaded = LoadConfigFromString(yaml, "calibration.yaml");
  EXPECT_EQ(loaded.backend.odometry_model, OdometryModel::kGyro);
  EXPECT_DOUBLE_EQ(loaded.backend.calibration_scale_mean, -0.00497512);
  EXPECT_DOUBLE_EQ(loaded.backend.calibration_rotation_mean, 0.0123457);
  EXPECT_EQ(loaded.backend.calibration_heading_drift_mean_rad_per_m, 0.0);
}

}  // namespace
}  // namespace uwbsar::slam
