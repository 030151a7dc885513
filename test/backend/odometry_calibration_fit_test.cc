#include "backend/odometry_calibration_fit.h"

#include <gtest/gtest.h>

#include <cstdio>
#include <vector>

#include "slam/errors.h"
#include "test/backend/calibration_routes.h"

namespace uwbsar {
namespace {

using testing::LShapeLap;
using testing::MeasuredStep;

struct Streams {
  std::vector<OdometrySample> odometry, truth;
};

/// `steps` driven at 50 Hz in pieces of 1/25, by a base with intrinsics `base`.
Streams Drive(const OdometryCalibration& base, const std::vector<Pose2>& steps) {
  Streams s;
  Pose2 odom, truth;
  TimestampNs t = 1'000'000'000;
  const auto sample = [&t](const Pose2& p) {
    OdometrySample o;
    o.stamp_ns = t;
    o.T_world_robot = p;
    return o;
  };
  s.odometry.push_back(sample(odom));
  s.truth.push_back(sample(truth));
  for (const Pose2& step : steps) {
    const Pose2 piece{step.x_m / 25, step.y_m / 25, step.yaw_rad / 25};
    for (int i = 0; i < 25; ++i) {
      t += 20'000'000;
      odom = odom * MeasuredStep(base, piece);
      truth = truth * piece;
      s.odometry.push_back(sample(odom));
      s.truth.push_back(sample(truth));
    }
  }
  return s;
}

TEST(OdometryCalibrationFitTest, RecoversTheBaseIntrinsicsFromALapWithGroundTruth) {
  const OdometryCalibration base{-0.004975, 0.003, 0.02};
  std::vector<Pose2> steps = LShapeLap(false);
  for (const Pose2& p : LShapeLap(true)) steps.push_back(p);
  const Streams run = Drive(base, steps);
  const CalibrationFit fit = FitOdometryCalibration(run.odometry, run.truth, BackendConfig{});
  std::printf(
      "fit: scale %.6f +- %.1e, drift %.6f +- %.1e, rotation %.5f +- %.1e; %d segments, "
      "%.1f m; segment error %.2f -> %.3f cm\n",
      fit.calibration[0], fit.sigma[0], fit.calibration[1], fit.sigma[1], fit.calibration[2],
      fit.sigma[2], fit.segments, fit.path_m, fit.xy_rms_before_m * 100, fit.xy_rms_after_m * 100);
  EXPECT_NEAR(fit.calibration[kCalibScale], base[kCalibScale], 1e-5);
  EXPECT_NEAR(fit.calibration[kCalibHeadingDrift], base[kCalibHeadingDrift], 1e-5);
  EXPECT_NEAR(fit.calibration[kCalibRotation], base[kCalibRotation], 1e-4);
  EXPECT_EQ(fit.observed, (std::array<bool, 3>{true, true, true}));
  EXPECT_NEAR(fit.path_m, 2 * 40.0 / (1 + base[kCalibScale]), 0.01);
  EXPECT_LT(fit.xy_rms_after_m, 0.1 * fit.xy_rms_before_m);
}

// A straight run observes the distance scale and the heading drift but not the turns: the
// rotation scale stays at its prior and is reported as not observed.
TEST(OdometryCalibrationFitTest, AStraightRunLeavesTheRotationAtItsPrior) {
  const OdometryCalibration base{0.01, -0.002, 0.0};
  const Streams run = Drive(base, std::vector<Pose2>(80, Pose2{0.5, 0.0, 0.0}));  // 40 m
  const CalibrationFit fit = FitOdometryCalibration(run.odometry, run.truth, BackendConfig{});
  EXPECT_NEAR(fit.calibration[kCalibScale], 0.01, 1e-5);
  EXPECT_NEAR(fit.calibration[kCalibHeadingDrift], -0.002, 1e-5);
  EXPECT_NEAR(fit.calibration[kCalibRotation], 0.0, 1e-6);
  EXPECT_EQ(fit.observed, (std::array<bool, 3>{true, true, false}));
}

TEST(OdometryCalibrationFitTest, TooLittleOverlapWithTheTruthIsRefusedWithTheCounts) {
  const Streams run = Drive({0, 0, 0}, std::vector<Pose2>(80, Pose2{0.5, 0.0, 0.0}));
  // The truth ends after 2 m: 4 segments of 0.5 m.
  const std::vector<OdometrySample> truth(run.truth.begin(), run.truth.begin() + 101);
  try {
    FitOdometryCalibration(run.odometry, truth, BackendConfig{});
    FAIL() << "expected InputError";
  } catch (const InputError& e) {
    EXPECT_NE(
        std::string(e.what()).find(": 4 segments of 0.5 m overlap the ground truth, at least 10"),
        std::string::npos)
        << e.what();
  }
  // A truth stream with a gap: the odometry inside it is skipped, not interpolated across.
  std::vector<OdometrySample> gappy = run.truth;
  gappy.erase(gappy.begin() + 100, gappy.begin() + 400);  // 2 m to 8 m
  const CalibrationFit fit = FitOdometryCalibration(run.odometry, gappy, BackendConfig{});
  // 3 segments before the gap (1.98 m, the last 0.48 m unused) and 64 after it (32 m).
  EXPECT_EQ(fit.segments, 3 + 64);
  EXPECT_NEAR(fit.path_m, 33.5, 1e-6);
}

}  // namespace
}  // namespace uwbsar
