// A gyro base's heading error is its bias over time (backend/gyro_bias_track.h): standstills
// measure it (backend/gyro_stillness.h), loops observe it through the odometry, and a drift per
// metre (the wheel-only model) cannot stand in for it when the speed varies or the robot turns
// on the spot.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <vector>

#include "backend/gyro_bias_track.h"
#include "backend/gyro_stillness.h"
#include "backend/pose_graph.h"
#include "calibration_routes.h"

namespace uwbsar {
namespace {

using testing::GraphAte;
using testing::LShapeLap;

constexpr double kRadPerDeg = M_PI / 180.0;

TEST(GyroStillnessTest, AStandstillMeasuresTheBiasAndATurnInPlaceDoesNot) {
  BackendConfig config;
  GyroStillness still(config);
  const double bias_radps = 0.05 * kRadPerDeg;
  double t = 0.0, yaw = 0.0, x = 0.0;
  std::vector<GyroStandstill> found;
  const auto add = [&](double dt, double dx, double dyaw) {
    t += dt, x += dx, yaw += dyaw;
    if (auto s = still.Add(t, Pose2{x, 0.0, yaw})) found.push_back(*s);
  };
  add(0.02, 0.0, 0.0);
  for (int i = 0; i < 250; ++i) add(0.02, 0.0, bias_radps * 0.02);       // 5 s still
  for (int i = 0; i < 100; ++i) add(0.02, 0.004, 0.0);                   // 2 s driving
  for (int i = 0; i < 100; ++i) add(0.02, 0.0, 10 * kRadPerDeg * 0.02);  // a turn in place
  for (int i = 0; i < 10; ++i) add(0.02, 0.0, bias_radps * 0.02);        // 0.2 s: too short
  for (int i = 0; i < 50; ++i) add(0.02, 0.004, 0.0);
  add(0.02, 0.004, 0.0);
  add(100.0, 0.0, 0.0);  // a gap in the odometry with the same pose on both sides: not still
  for (int i = 0; i < 10; ++i) add(0.02, 0.004, 0.0);
  for (int i = 0; i < 100; ++i) add(0.02, 0.0, -bias_radps * 0.02);  // 2 s still at the end
  if (auto s = still.Flush()) found.push_back(*s);
  ASSERT_EQ(found.size(), 2u);
  EXPECT_NEAR(found[0].end_s - found[0].begin_s, 5.0, 1e-9);
  EXPECT_NEAR(found[0].bias_radps, bias_radps, 1e-12);
  EXPECT_NEAR(found[0].sigma_radps, 0.03 * kRadPerDeg / std::sqrt(5.0), 1e-12);
  EXPECT_NEAR(found[1].bias_radps, -bias_radps, 1e-12);
  EXPECT_NEAR(found[1].end_s - found[1].begin_s, 2.0, 1e-9);
}

TEST(GyroBiasTrackTest, SegmentsAreMadeWhereNeededAndTiedByTheWalk) {
  ceres::Problem problem;
  BackendConfig config;
  config.gyro_bias_segment_s = 10.0;
  GyroBiasTrack track(&problem, config);
  double* b25 = track.BlockAt(25.0);
  EXPECT_EQ(track.BlockAt(29.9), b25);
  track.BlockAt(55.0);  // segment 5, tied to 2
  track.BlockAt(3.0);   // segment 0, tied to 2
  track.BlockAt(12.0);  // segment 1 between them: the walk 0 -> 2 becomes 0 -> 1 -> 2
  EXPECT_EQ(track.Segments().size(), 4u);
  EXPECT_EQ(problem.NumParameterBlocks(), 4);
  EXPECT_EQ(problem.NumResidualBlocks(), 4);  // the turn-on prior and 3 walks
  // A stray stamp decades away is one more segment, weakly tied, not millions.
  track.BlockAt(-1.7e9);
  EXPECT_EQ(problem.NumParameterBlocks(), 5);
  EXPECT_EQ(problem.NumResidualBlocks(), 5);
  track.AddMeasurement(51.0, 0.001, 0.0001);
  ceres::Solver::Options options;
  ceres::Solver::Summary summary;
  ceres::Solve(options, &problem, &summary);
  // The measurement pulls its segment; the walk carries it to the others, fading with time.
  const std::vector<std::pair<double, double>> s = track.Segments();
  EXPECT_NEAR(s.back().second, 0.001, 5e-5);  // the turn-on prior pulls a little
  EXPECT_LT(s.front().second, s.back().second);
  EXPECT_GT(s.front().second, 0.0);
  EXPECT_GT(track.Chi2(), 0.0);
  double cost = 0.0;
  problem.Evaluate(ceres::Problem::EvaluateOptions(), &cost, nullptr, nullptr, nullptr);
  EXPECT_NEAR(track.Chi2(), 2.0 * cost, 1e-9 * track.Chi2());  // every term counted once
  // Without a walk the bias is one constant: one segment.
  config.gyro_bias_walk_dps_per_sqrt_s = 0.0;
  ceres::Problem p2;
  GyroBiasTrack constant(&p2, config);
  EXPECT_EQ(constant.BlockAt(0.0), constant.BlockAt(1e4));
}

/// The L-shaped floor out at `out_mps` and back at `back_mps` (calibration_routes.h), turning on
/// the spot at 10 deg/s, with a gyro whose bias is `bias_dps`: each step's heading carries
/// bias * its time.
struct GyroRun {
  std::vector<Pose2> truth, measured;
  std::vector<double> times_s;  ///< node times
};

GyroRun DriveWithGyro(double bias_dps, double out_mps, double back_mps) {
  std::vector<Pose2> steps = LShapeLap(false);
  const std::size_t lap = steps.size();
  for (const Pose2& s : LShapeLap(true)) steps.push_back(s);
  GyroRun run;
  Pose2 p;
  double t = 10.0;
  run.truth.push_back(p);
  run.times_s.push_back(t);
  for (const Pose2& step : steps) {
    const double speed_mps = run.measured.size() < lap ? out_mps : back_mps;
    const double dt =
        std::hypot(step.x_m, step.y_m) / speed_mps + std::abs(step.yaw_rad) / (10 * kRadPerDeg);
    const double error = bias_dps * kRadPerDeg * dt;
    // The gyro's heading error turns the chord by half of it (midpoint integration).
    const double c = std::cos(0.5 * error), s = std::sin(0.5 * error);
    run.measured.push_back(
        {c * step.x_m - s * step.y_m, s * step.x_m + c * step.y_m, step.yaw_rad + error});
    p = p * step;
    t += dt;
    run.truth.push_back(p);
    run.times_s.push_back(t);
  }
  return run;
}

/// The chain with the nodes' times, and the loops of the way back to the way out; `standstill`
/// adds a measurement of the bias as a 10 s standstill before the start would give.
double MapAte(const GyroRun& run, OdometryModel model, bool loops, double standstill_bias_dps,
              double* bias_out_dps = nullptr) {
  BackendConfig config;
  config.odometry_model = model;
  PoseGraph g(config);
  Pose2 odom;
  g.AddNode(0, odom);
  for (std::size_t k = 0; k < run.measured.size(); ++k) {
    odom = odom * run.measured[k];
    g.AddNode(static_cast<int>(k + 1), odom);
    g.AddOdometryEdge(static_cast<int>(k), static_cast<int>(k + 1), run.measured[k], 0, -1.0,
                      std::numeric_limits<double>::quiet_NaN(), run.times_s[k], run.times_s[k + 1]);
  }
  if (std::isfinite(standstill_bias_dps)) {
    g.AddGyroBiasMeasurement(0, 5.0, standstill_bias_dps * kRadPerDeg,
                             0.03 * kRadPerDeg / std::sqrt(10.0));
  }
  const int n = static_cast<int>(run.truth.size());
  for (int k = n / 2 + 1; loops && k < n; k += 4) {
    for (int o = 0; o < n / 2; ++o) {
      const Pose2 d = Between(run.truth[o], run.truth[k]);
      if (std::hypot(d.x_m, d.y_m) < 1e-6) {
        g.AddLoopEdge(k, o, Between(run.truth[k], run.truth[o]));
        break;
      }
    }
  }
  g.Optimize();
  if (bias_out_dps != nullptr) {
    const auto biases = g.GyroBiases();
    *bias_out_dps = biases.empty() ? 0.0 : biases.at(0).front().second / kRadPerDeg;
  }
  return GraphAte(g, run.truth);
}

TEST(PoseGraphGyroTest, LoopsEstimateTheRunsBiasWhereADriftPerMetreCannot) {
  // Out at 0.2 m/s, back slowly at 0.08 m/s (1000 s in all), with a bias of +0.06 deg/s
  // (2 sigma of the turn-on bias): per metre, the heading error of the way back is 2.5 times
  // the way out's.
  const GyroRun run = DriveWithGyro(0.06, 0.2, 0.08);
  const double odometry = MapAte(run, OdometryModel::kGyro, false, NAN);
  double bias_dps = 0.0;
  const double gyro = MapAte(run, OdometryModel::kGyro, true, NAN, &bias_dps);
  const double wheel = MapAte(run, OdometryModel::kWheel, true, NAN);
  std::printf(
      "odometry %.2f cm; with loops: gyro model %.2f cm (bias %.4f deg/s), wheel model "
      "%.2f cm\n",
      100 * odometry, 100 * gyro, bias_dps, 100 * wheel);
  EXPECT_NEAR(bias_dps, 0.06, 0.01);
  EXPECT_LT(gyro, 0.01);
  EXPECT_LT(gyro * 3, wheel);
  EXPECT_LT(wheel, odometry);
}

TEST(PoseGraphGyroTest, AStandstillCorrectsTheOdometryWithoutLoops) {
  const GyroRun run = DriveWithGyro(-0.06, 0.2, 0.2);
  const double odometry = MapAte(run, OdometryModel::kGyro, false, NAN);
  double bias_dps = 0.0;
  // The standstill's measurement, off by one sigma of its own noise.
  const double still =
      MapAte(run, OdometryModel::kGyro, false, -0.06 + 0.03 / std::sqrt(10.0), &bias_dps);
  std::printf("no loops: odometry %.2f cm, with the standstill %.2f cm (bias %.4f deg/s)\n",
              100 * odometry, 100 * still, bias_dps);
  EXPECT_LT(still * 3, odometry);
  // Between the turn-on prior (0 +- 0.03) and the measurement (-0.0505 +- 0.0095): -0.046.
  EXPECT_NEAR(bias_dps, -0.046, 0.002);
}

}  // namespace
}  // namespace uwbsar
