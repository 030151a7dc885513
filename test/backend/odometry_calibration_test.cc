#include "backend/odometry_calibration.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <stdexcept>

#include "backend/pose_graph.h"
#include "backend/se2_edge_cost.h"
#include "test/backend/calibration_routes.h"

namespace uwbsar {
namespace {

using testing::BuildOdometryChain;
using testing::DriveSteps;
using testing::GraphAte;
using testing::LShapeLap;
using testing::MeasuredStep;
using testing::OdometryRun;

/// The L-shaped lap driven forward, then backward.
OdometryRun OutAndBack(const OdometryCalibration& calibration) {
  std::vector<Pose2> steps = LShapeLap(false);
  for (const Pose2& s : LShapeLap(true)) steps.push_back(s);
  return DriveSteps(calibration, steps);
}

/// The odometry chain and, with `loops`, a loop from every 4th node of the way back to the
/// node of the way out at the same place.
void Build(const OdometryRun& run, bool loops, PoseGraph* g) {
  BuildOdometryChain(run, g);
  const int n = static_cast<int>(run.truth.size());
  const int half = n / 2;
  for (int k = half + 1; loops && k < n; k += 4) {
    for (int o = 0; o < half; ++o) {
      const Pose2 d = Between(run.truth[o], run.truth[k]);
      if (std::hypot(d.x_m, d.y_m) < 1e-6) {
        g->AddLoopEdge(k, o, Between(run.truth[k], run.truth[o]));
        break;
      }
    }
  }
}

TEST(OdometryCalibrationTest, ZeroCalibrationIsThePlainSe2Residual) {
  const Pose2 T_a_b{0.8, -0.2, 0.3};
  const Eigen::Matrix3d U = *SqrtInformation(Eigen::Vector3d(30, 40, 90).asDiagonal());
  const double a[3] = {1.0, 2.0, 0.4}, b[3] = {1.9, 2.1, 0.9};
  EXPECT_NEAR(CalibratedOdometryChi2(a, b, {0, 0, 0}, T_a_b, TravelOf(T_a_b), U),
              Se2Chi2(a, b, T_a_b, U), 1e-12);
}

TEST(OdometryCalibrationTest, CorrectionUndoesScaleDriftAndRotationErrors) {
  const OdometryCalibration calibration{-0.01, 0.004, 0.03};
  for (const Pose2& truth :
       {Pose2{0.5, 0.0, 0.0}, Pose2{0.0, 0.0, M_PI / 2}, Pose2{0.7, 0.1, 0.2}}) {
    const Pose2 measured = MeasuredStep(calibration, truth);
    const Pose2 corrected = CorrectedOdometryStep(calibration, measured);
    EXPECT_NEAR(corrected.x_m, truth.x_m, 1e-12);
    EXPECT_NEAR(corrected.y_m, truth.y_m, 1e-12);
    EXPECT_NEAR(corrected.yaw_rad, truth.yaw_rad, 1e-12);
  }
  // A straight metre: the right wheel's longer travel reads as a turn of drift * 1 m.
  const Pose2 straight = MeasuredStep(calibration, {1.0, 0.0, 0.0});
  EXPECT_NEAR(straight.yaw_rad, 0.004 / 0.99 / 1.03, 1e-12);
}

// Loops between the way out and the way back at the same places observe the heading drift
// (it turns the same way on both passes) and the rotation scale (the turns go the other way
// round): both are recovered. The distance scale is not observable by loops whose two ends
// coincide (a uniformly scaled map satisfies them all): it stays at its prior, as it does on
// the tours.
TEST(OdometryCalibrationTest, LoopsRecoverAsymmetricDriftAndWheelbase) {
  const OdometryCalibration truth_calibration{0.0, 0.004, 0.03};
  const OdometryRun run = OutAndBack(truth_calibration);
  BackendConfig config;
  config.odometry_model = OdometryModel::kWheel;  // a drift per metre: a wheel-only base's
  config.calibration_rotation_sigma = 0.05;       // observable here (the default holds it near 0)
  PoseGraph calibrated(config);
  Build(run, true, &calibrated);
  const OptimizeResult r = calibrated.Optimize();
  EXPECT_TRUE(r.converged) << r.termination;
  EXPECT_TRUE(r.rejected.empty());
  const OdometryCalibration estimate = calibrated.OdometryCalibrations().at(0);
  std::printf("estimate: scale %.5f, drift %.5f rad/m, rotation %.5f\n", estimate[0], estimate[1],
              estimate[2]);
  EXPECT_NEAR(estimate[kCalibScale], 0.0, 1e-4);
  EXPECT_NEAR(estimate[kCalibHeadingDrift], 0.004, 0.0004);
  EXPECT_NEAR(estimate[kCalibRotation], 0.03, 0.003);

  BackendConfig off = config;
  off.odometry_calibration = false;
  PoseGraph plain(off);
  Build(run, true, &plain);
  plain.Optimize();
  EXPECT_TRUE(plain.OdometryCalibrations().empty());
  const double ate_plain = GraphAte(plain, run.truth),
               ate_calibrated = GraphAte(calibrated, run.truth);
  std::printf("ATE with calibration %.2f cm, without %.2f cm\n", ate_calibrated * 100,
              ate_plain * 100);
  EXPECT_LT(ate_calibrated, 0.01);
  EXPECT_GT(ate_plain, 3 * ate_calibrated);
}

TEST(OdometryCalibrationTest, WithoutLoopsTheCalibrationStaysAtThePrior) {
  const OdometryRun run = OutAndBack({-0.01, 0.004, 0.03});
  PoseGraph g;
  Build(run, false, &g);
  std::map<int, Pose2> before = g.GetPoses();
  g.Optimize();
  const OdometryCalibration estimate = g.OdometryCalibrations().at(0);
  EXPECT_EQ(estimate[kCalibScale], 0.0);
  EXPECT_EQ(estimate[kCalibHeadingDrift], 0.0);
  EXPECT_EQ(estimate[kCalibRotation], 0.0);
  for (const auto& [id, p] : g.GetPoses()) {
    EXPECT_NEAR(p.x_m, before[id].x_m, 1e-6) << id;  // the odometry, uncorrected
    EXPECT_NEAR(p.y_m, before[id].y_m, 1e-6) << id;
  }
}

// A base calibrated once (backend.calibration_*_mean): without any loop the odometry is
// corrected by it, and the trajectory is the truth; uncalibrated, the same run is off by
// decimetres.
TEST(OdometryCalibrationTest, AGivenCalibrationCorrectsTheOdometryWithoutLoops) {
  const OdometryCalibration base{-0.01, 0.004, 0.03};
  const OdometryRun run = OutAndBack(base);
  BackendConfig config;
  config.calibration_scale_mean = base[kCalibScale];
  config.calibration_heading_drift_mean_rad_per_m = base[kCalibHeadingDrift];
  config.calibration_rotation_mean = base[kCalibRotation];
  PoseGraph calibrated(config);
  Build(run, false, &calibrated);
  calibrated.Optimize();
  EXPECT_EQ(calibrated.OdometryCalibrations().at(0), base);
  PoseGraph plain;
  Build(run, false, &plain);
  plain.Optimize();
  const double ate_calibrated = GraphAte(calibrated, run.truth),
               ate_plain = GraphAte(plain, run.truth);
  std::printf("ATE calibrated %.2e m, uncalibrated %.2f cm\n", ate_calibrated, ate_plain * 100);
  EXPECT_LT(ate_calibrated, 1e-9);
  EXPECT_GT(ate_plain, 0.05);
}

// The distance scale, which loops cannot observe (above), comes from the given calibration
// when the prior is as tight as the calibration is good: with loops, the scale stays at the
// given value and the drift and rotation are still estimated.
TEST(OdometryCalibrationTest, WithLoopsAGivenScaleHoldsAndTheRestIsEstimated) {
  const OdometryCalibration base{-0.01, 0.004, 0.03};
  const OdometryRun run = OutAndBack(base);
  BackendConfig config;
  config.odometry_model = OdometryModel::kWheel;  // a drift per metre: a wheel-only base's
  config.calibration_scale_mean = -0.01;
  config.calibration_scale_sigma = 0.001;
  config.calibration_rotation_sigma = 0.05;
  PoseGraph g(config);
  Build(run, true, &g);
  const OptimizeResult r = g.Optimize();
  EXPECT_TRUE(r.converged) << r.termination;
  const OdometryCalibration estimate = g.OdometryCalibrations().at(0);
  EXPECT_NEAR(estimate[kCalibScale], -0.01, 1e-4);
  EXPECT_NEAR(estimate[kCalibHeadingDrift], 0.004, 0.0004);
  EXPECT_NEAR(estimate[kCalibRotation], 0.03, 0.003);

  BackendConfig uncalibrated = config;  // the scale's prior at 0, as tight: the map is scaled
  uncalibrated.calibration_scale_mean = 0.0;
  PoseGraph u(uncalibrated);
  Build(run, true, &u);
  u.Optimize();
  const double ate_m = GraphAte(g, run.truth), ate_uncalibrated_m = GraphAte(u, run.truth);
  std::printf("ATE with the scale given %.2f cm, with scale 0 %.2f cm\n", ate_m * 100,
              ate_uncalibrated_m * 100);
  EXPECT_LT(ate_m, 0.005);
  EXPECT_GT(ate_uncalibrated_m, 2 * ate_m);
}

// AddOdometryNode predicts the new node on the odometry corrected by the base's calibration
// mean, with the path and turn given (keyframe anchors keep the world orientation), and adds
// the same odometry edge as AddOdometryEdge; switched off, the step is taken as measured.
TEST(OdometryCalibrationTest, AnOdometryNodeStartsOnTheCorrectedStepWithItsEdge) {
  BackendConfig config;
  config.odometry_model = OdometryModel::kWheel;  // a drift per metre: a wheel-only base's
  config.calibration_scale_mean = -0.01;
  config.calibration_heading_drift_mean_rad_per_m = 0.004;
  config.calibration_rotation_mean = 0.03;
  const Pose2 origin{2.0, -1.0, 0.3}, step{1.0, 0.2, 0.0};
  const double path_m = 1.1, turn_rad = 0.25;
  PoseGraph g(config);
  g.AddNode(0, origin);
  const Pose2 estimate = g.AddOdometryNode(0, 1, step, 0, path_m, turn_rad);
  const Pose2 expected =
      origin * CorrectedOdometryStep(config.CalibrationMean(), step, {path_m, turn_rad});
  EXPECT_EQ(estimate.x_m, expected.x_m);
  EXPECT_EQ(estimate.y_m, expected.y_m);
  EXPECT_EQ(estimate.yaw_rad, expected.yaw_rad);
  EXPECT_GT(std::hypot(estimate.x_m - (origin * step).x_m, estimate.y_m - (origin * step).y_m),
            1e-3);
  EXPECT_EQ(g.GetPose(1).x_m, expected.x_m);
  PoseGraph reference(config);
  reference.AddNode(0, origin);
  reference.AddNode(1, expected, false);
  reference.AddOdometryEdge(0, 1, step, 0, path_m, turn_rad);
  ASSERT_EQ(g.Edges().size(), 1u);
  EXPECT_EQ(g.Edges()[0].path_m, path_m);
  EXPECT_EQ(g.Edges()[0].turn_rad, turn_rad);
  EXPECT_EQ(g.Edges()[0].information, reference.Edges()[0].information);

  config.odometry_calibration = false;
  PoseGraph plain(config);
  plain.AddNode(0, origin);
  const Pose2 measured = plain.AddOdometryNode(0, 1, step, 0, path_m, turn_rad);
  EXPECT_EQ(measured.x_m, (origin * step).x_m);
  EXPECT_EQ(measured.yaw_rad, (origin * step).yaw_rad);
  EXPECT_THROW(plain.AddOdometryNode(7, 8, step), std::out_of_range);
  EXPECT_FALSE(plain.HasNode(8));
}

TEST(OdometryCalibrationTest, ThePriorIsCentredOnItsMean) {
  const OdometryCalibrationPrior prior({-0.01, 0.002, 0.03}, Eigen::Vector3d(0.01, 0.001, 0.1));
  EXPECT_EQ(prior.Chi2({-0.01, 0.002, 0.03}), 0.0);
  EXPECT_NEAR(prior.Chi2({0.0, 0.002, 0.03}), 1.0, 1e-12);
  EXPECT_NEAR(prior.Chi2({-0.01, 0.0, 0.13}), 4.0 + 1.0, 1e-12);
}

TEST(OdometryCalibrationTest, EdgesWithoutATrajectoryAreNotCalibrated) {
  // g2o data sets (AddEdge) carry their own odometry model: no calibration block.
  PoseGraph g;
  g.AddNode(0, {});
  g.AddNode(1, {1, 0, 0});
  PoseGraphEdge e;
  e.from_id = 0;
  e.to_id = 1;
  e.T_from_to = {1, 0, 0};
  e.kind = EdgeKind::kOdometry;
  g.AddEdge(e);
  g.Optimize();
  EXPECT_TRUE(g.OdometryCalibrations().empty());
}

}  // namespace
}  // namespace uwbsar
