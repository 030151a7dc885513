#include "backend/odometry_calibration_fit.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "core/errors.h"
#include "test/backend/calibration_routes.h"

namespace uwbsar {
namespace {

using testing::LShapeLap;
using testing::MeasuredStep;

struct Streams {
  std::vector<OdometrySample> odometry, truth;
};

/// What a gyro base reports for the true piece `truth` of `dt_s` seconds: the heading turned
/// by (1 + rotation) and the gyro's bias over the time (the exact inverse of
/// CorrectOdometryStep with the bias).
Pose2 GyroMeasuredStep(const OdometryCalibration& base, double bias_radps, double dt_s,
                       const Pose2& truth) {
  const double k = 1.0 / (1.0 + base[kCalibScale]);
  const double yaw = (truth.yaw_rad + bias_radps * dt_s) / (1.0 + base[kCalibRotation]);
  const double half_turn = 0.5 * (truth.yaw_rad - yaw);
  const double c = std::cos(half_turn), s = std::sin(half_turn);
  return {k * (c * truth.x_m + s * truth.y_m), k * (-s * truth.x_m + c * truth.y_m), yaw};
}

/// `steps` driven at 50 Hz in pieces of 1/25, by a base with intrinsics `base` (and, when
/// `gyro_bias_radps` is given, a gyro's heading with that bias instead of a drift per metre).
Streams Drive(const OdometryCalibration& base, const std::vector<Pose2>& steps,
              std::optional<double> gyro_bias_radps = std::nullopt) {
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
      odom = odom * (gyro_bias_radps ? GyroMeasuredStep(base, *gyro_bias_radps, 0.02, piece)
                                     : MeasuredStep(base, piece));
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
  // Its corners are turned on the spot: a drift per metre explains the heading, a bias over
  // time does not.
  EXPECT_EQ(fit.model, OdometryModel::kWheel);
  EXPECT_EQ(fit.evidence.decided_by, "residuals");
  EXPECT_GT(fit.evidence.gyro_chi2, 25.0 + fit.evidence.wheel_chi2);
}

/// The L-shaped lap both ways with a 2 s standstill at the start and at every 8th step.
std::vector<Pose2> LapWithStandstills() {
  std::vector<Pose2> steps(4, Pose2{});
  for (const bool reverse : {false, true}) {
    for (const Pose2& p : LShapeLap(reverse)) {
      steps.push_back(p);
      if (steps.size() % 8 == 0) steps.insert(steps.end(), 4, Pose2{});
    }
  }
  return steps;
}

// Issue 44: a gyro base's heading error is its bias over time (standstills included), which
// belongs to the run. The fit finds the kind of base, the robot's distance scale and turn
// scale, and the run's bias, and holds the drift per metre at 0.
TEST(OdometryCalibrationFitTest, AGyroBaseGivesItsScalesAndTheRunsBiasAndNoDriftPerMetre) {
  const OdometryCalibration base{-0.004975, 0.0, 0.02};
  const double bias = 0.042 * M_PI / 180;  // 0.042 deg/s
  const Streams run = Drive(base, LapWithStandstills(), bias);
  const CalibrationFit fit = FitOdometryCalibration(run.odometry, run.truth, BackendConfig{});
  EXPECT_EQ(fit.model, OdometryModel::kGyro);
  EXPECT_EQ(fit.evidence.decided_by, "residuals");
  EXPECT_GT(fit.evidence.wheel_chi2, 25.0 + fit.evidence.gyro_chi2);
  EXPECT_GT(fit.evidence.still_s, 30.0);
  // At rest the heading turns at the bias, reported through the turns' scale.
  EXPECT_NEAR(fit.evidence.still_turn_rad, bias * fit.evidence.still_s / 1.02, 1e-6);
  EXPECT_NEAR(fit.calibration[kCalibScale], base[kCalibScale], 1e-5);
  EXPECT_NEAR(fit.calibration[kCalibRotation], base[kCalibRotation], 1e-4);
  EXPECT_EQ(fit.calibration[kCalibHeadingDrift], 0.0);
  EXPECT_EQ(fit.observed, (std::array<bool, 3>{true, false, true}));
  // One bias per 30 s of the run (about 190 s), all the run's constant one.
  EXPECT_GE(fit.gyro_bias_segments.size(), 6u);
  for (const auto& [t, b] : fit.gyro_bias_segments) EXPECT_NEAR(b, bias, 2e-6) << t;
  EXPECT_NEAR(fit.gyro_bias_mean_radps, bias, 1e-6);
  EXPECT_LT(fit.gyro_bias_spread_radps, 1e-6);
  EXPECT_LT(fit.xy_rms_after_m, 0.1 * fit.xy_rms_before_m);
  // Told it is a wheel base, the same run fits worse.
  CalibrationFitOptions wheel;
  wheel.model = OdometryModel::kWheel;
  const CalibrationFit told = FitOdometryCalibration(run.odometry, run.truth, {}, wheel);
  EXPECT_EQ(told.model, OdometryModel::kWheel);
  EXPECT_EQ(told.evidence.decided_by, "told");
  EXPECT_GT(told.yaw_rms_after_rad, 10 * fit.yaw_rms_after_rad);
}

// When time and path grow together (one speed, no standstill, no turn on the spot), a bias
// per second and a drift per metre explain the run alike: standstills decide, and without
// them the configured model.
TEST(OdometryCalibrationFitTest, WhenTheResidualsCannotTellTheStandstillsOrTheConfigurationDo) {
  const std::vector<Pose2> straight(80, Pose2{0.5, 0.0, 0.0});
  const Streams wheel = Drive({0.01, -0.002, 0.0}, straight);
  for (const OdometryModel configured : {OdometryModel::kGyro, OdometryModel::kWheel}) {
    BackendConfig priors;
    priors.odometry_model = configured;
    const CalibrationFit fit = FitOdometryCalibration(wheel.odometry, wheel.truth, priors);
    EXPECT_EQ(fit.evidence.decided_by, "configuration");
    EXPECT_EQ(fit.model, configured);
  }
  // A standstill, and the same ambiguous run after it: a wheel base's heading does not move at
  // rest, a gyro's turns at its bias.
  std::vector<Pose2> with_pause(10, Pose2{});
  with_pause.insert(with_pause.end(), straight.begin(), straight.end());
  const Streams paused_wheel = Drive({0.01, -0.002, 0.0}, with_pause);
  std::vector<OdometrySample> truth(paused_wheel.truth.begin() + 250, paused_wheel.truth.end());
  // The truth only from where the base moves: the standstill lies outside every segment.
  const CalibrationFit w = FitOdometryCalibration(paused_wheel.odometry, truth, BackendConfig{});
  EXPECT_EQ(w.evidence.decided_by, "standstills");
  EXPECT_NEAR(w.evidence.still_s, 5.0, 0.03);
  EXPECT_EQ(w.evidence.still_turn_rad, 0.0);
  EXPECT_EQ(w.model, OdometryModel::kWheel);
  const Streams paused_gyro = Drive({0.01, 0.0, 0.0}, with_pause, 0.0005);
  const CalibrationFit g = FitOdometryCalibration(paused_gyro.odometry, truth, BackendConfig{});
  EXPECT_EQ(g.evidence.decided_by, "standstills");
  EXPECT_EQ(g.model, OdometryModel::kGyro);
  EXPECT_NEAR(g.gyro_bias_mean_radps, 0.0005, 1e-7);
}

// A straight run observes the distance scale and the heading drift but not the turns: the
// rotation scale stays at its prior and is reported as not observed.
TEST(OdometryCalibrationFitTest, AStraightRunLeavesTheRotationAtItsPrior) {
  const OdometryCalibration base{0.01, -0.002, 0.0};
  const Streams run = Drive(base, std::vector<Pose2>(80, Pose2{0.5, 0.0, 0.0}));  // 40 m
  // One speed and no standstill: nothing tells a drift per metre from a bias per second.
  CalibrationFitOptions wheel;
  wheel.model = OdometryModel::kWheel;
  const CalibrationFit fit =
      FitOdometryCalibration(run.odometry, run.truth, BackendConfig{}, wheel);
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

/// The message FitOdometryCalibration refuses the streams with ("" if it fits).
std::string RefusalOf(const std::vector<OdometrySample>& odometry,
                      const std::vector<OdometrySample>& truth) {
  CalibrationFitOptions options;
  options.odometry_source = "run.bag";
  options.truth_source = "truth.tum";
  try {
    FitOdometryCalibration(odometry, truth, BackendConfig{}, options);
  } catch (const InputError& e) {
    return e.what();
  }
  return "";
}

Streams StraightRun() { return Drive({0, 0, 0}, std::vector<Pose2>(80, Pose2{0.5, 0.0, 0.0})); }

// An odometry reset (the base restarted mid-run) fitted a scale of -0.337 with exit 0.
TEST(OdometryCalibrationFitTest, AnOdometryResetIsRefusedNamingTheSample) {
  Streams run = StraightRun();
  const Pose2 at_reset = run.odometry[1000].T_world_robot;  // 20 m along
  for (std::size_t i = 1000; i < run.odometry.size(); ++i) {
    run.odometry[i].T_world_robot = Between(at_reset, run.odometry[i].T_world_robot);
  }
  const std::string msg = RefusalOf(run.odometry, run.truth);
  EXPECT_EQ(msg.rfind("run.bag: odometry jumps 19.980 m and 0.000 rad in 0.020 s at t=21.000000 s "
                      "(sample 1000): a reset or two runs in one recording",
                      0),
            0u)
      << msg;
}

// Issue 45 item 7: a 3 m jump in the ground truth fitted half the real scale (sigma 0.72) with
// exit 0. The truth's steps are held to the odometry's rule, where the fit interpolates.
TEST(OdometryCalibrationFitTest, AGroundTruthJumpIsRefusedNamingTheLineAndTheStamp) {
  Streams run = StraightRun();
  for (std::size_t i = 1000; i < run.truth.size(); ++i) run.truth[i].T_world_robot.x_m += 3.0;
  EXPECT_EQ(RefusalOf(run.odometry, run.truth)
                .rfind("truth.tum: ground truth jumps 3.020 m and 0.000 rad in 0.020 s at "
                       "t=21.000000 s (sample 1000): a reset or two runs in one recording",
                       0),
            0u)
      << RefusalOf(run.odometry, run.truth);
  CalibrationFitOptions options;
  options.truth_source = "truth.tum";
  for (std::size_t i = 0; i < run.truth.size(); ++i) {
    options.truth_lines.push_back(static_cast<int>(i) + 3);  // two comment lines first
  }
  try {
    FitOdometryCalibration(run.odometry, run.truth, BackendConfig{}, options);
    ADD_FAILURE() << "expected InputError";
  } catch (const InputError& e) {
    EXPECT_EQ(std::string(e.what()).rfind("truth.tum:1003: ground truth jumps 3.020 m", 0), 0u)
        << e.what();
  }
  // A gap in the truth is no jump: the fit does not interpolate across it.
  Streams gappy = StraightRun();
  gappy.truth.erase(gappy.truth.begin() + 100, gappy.truth.begin() + 400);
  EXPECT_EQ(RefusalOf(gappy.odometry, gappy.truth), "");
}

TEST(OdometryCalibrationFitTest, StampsGoingBackAreRefused) {
  Streams run = StraightRun();
  std::swap(run.odometry[300].stamp_ns, run.odometry[301].stamp_ns);
  EXPECT_EQ(RefusalOf(run.odometry, run.truth),
            "run.bag: stamps go back at sample 301 (t=7.000000 s after t=7.020000 s): "
            "interleaved or merged recordings; calibrate needs one run in time order");
  run = StraightRun();
  std::swap(run.truth[5], run.truth[6]);
  EXPECT_EQ(RefusalOf(run.odometry, run.truth).rfind("truth.tum: stamps go back at sample 6", 0),
            0u);
}

// Ground truth that never moves fitted a scale of -1.000000 +- 0.
TEST(OdometryCalibrationFitTest, GroundTruthThatDoesNotMoveIsRefused) {
  Streams run = StraightRun();
  for (OdometrySample& t : run.truth) t.T_world_robot = Pose2{3.0, 4.0, 0.5};
  const std::string msg = RefusalOf(run.odometry, run.truth);
  EXPECT_EQ(msg.rfind("truth.tum: the ground truth does not move: 0.000 m over the 80 segments "
                      "where the odometry travels 40.000 m",
                      0),
            0u)
      << msg;
}

TEST(OdometryCalibrationFitTest, PathsOfImplausiblyDifferentLengthAreRefused) {
  Streams run = StraightRun();
  for (OdometrySample& t : run.truth) {
    t.T_world_robot.x_m *= 2.0;
    t.T_world_robot.y_m *= 2.0;
  }
  const std::string msg = RefusalOf(run.odometry, run.truth);
  EXPECT_NE(msg.find("run.bag: the odometry travels 40.000 m where the ground truth (truth.tum) "
                     "travels 80.000 m, a ratio of 0.500"),
            std::string::npos)
      << msg;
}

// A fit the configuration would refuse to load is never reported (it was written with --out).
TEST(OdometryCalibrationFitTest, AFitOutsideWhatTheConfigurationAcceptsIsRefused) {
  Streams run = StraightRun();
  for (OdometrySample& t : run.truth) {
    t.T_world_robot.x_m *= 1.3;
    t.T_world_robot.y_m *= 1.3;
  }
  const std::string msg = RefusalOf(run.odometry, run.truth);
  EXPECT_EQ(msg.rfind("run.bag: the fitted backend.calibration_scale_mean is 0.300000, outside "
                      "[-0.200000, 0.200000] that the configuration accepts",
                      0),
            0u)
      << msg;
  // 10 % is a (poor) base, not an error.
  for (OdometrySample& t : run.truth) {
    t.T_world_robot.x_m *= 1.1 / 1.3;
    t.T_world_robot.y_m *= 1.1 / 1.3;
  }
  EXPECT_EQ(RefusalOf(run.odometry, run.truth), "");
}

// A bag holding two recordings interleaved in time (merged by log time) fitted 1004 segments
// over 1603 m of a 6 m run: its odometry alternates between the runs, a jump at every switch.
TEST(OdometryCalibrationFitTest, TwoRunsInterleavedInTimeAreRefused) {
  const Streams first = StraightRun();
  Streams second = StraightRun();
  Streams merged;
  for (std::size_t i = 0; i < first.odometry.size(); ++i) {
    // The second run started 5 s later: at the same stamp it is 2.5 m behind.
    OdometrySample late = second.odometry[i];
    late.stamp_ns += 10'000'000;  // 10 ms after the first run's sample
    late.T_world_robot.x_m -= 2.5;
    merged.odometry.push_back(first.odometry[i]);
    merged.odometry.push_back(late);
  }
  const std::string msg = RefusalOf(merged.odometry, first.truth);
  EXPECT_EQ(msg.rfind("run.bag: odometry jumps 2.500 m and 0.000 rad in 0.010 s at t=1.010000 s "
                      "(sample 1)",
                      0),
            0u)
      << msg;
}

}  // namespace
}  // namespace uwbsar
