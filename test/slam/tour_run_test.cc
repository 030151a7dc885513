// A ring closed only after 50 m on a generated building floor
// (config/maps/tours/two_rings.yaml, the west ring of the figure of eight, 55 m), mapped
// with the default configuration: the ring's closure itself is accepted (a loop between
// the tour's start and its end), no false loop, SLAM beats odometry alone, and the wall
// edges of the straight stretches (slam/wall_edges.h) measure the sideways offsets to
// within a few centimetres. Measured (seed 1): 9 loops, 87 wall edges (none rejected, error
// 1.2 cm rms, 3.4 cm at most against the truth), ATE 4.29 cm against 12.34 cm of odometry
// (2.9x). Before the wall edges: 6.24 cm (2.0x), as one ring closure cannot tell the heading
// drift per metre from the turns' scale error; the odometry on this short ring is already
// good, so the 3x of the tour bench is not asked here. The full set of tours and seeds is
// `uwbsar_bench --benchmark_filter=Tour`.
// The second test maps floor50's tour with a base calibrated on another map's run; the third
// localises a run in a calibrated map of hall_wing, where the map's walls hold it between loops.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <vector>

#include "app/app_config_io.h"
#include "backend/odometry_calibration_fit.h"
#include "eval/tour/tour_eval.h"
#include "slam/app_config.h"
#include "slam/jobs/calibrate_job.h"
#include "slam/localization/localize_job.h"
#include "slam/outputs/session_capture.h"
#include "test/slam/simulated_calibration.h"

namespace uwbsar {
namespace {

std::string ToursFile(const std::string& name) {
  return std::string(UWBSAR_SOURCE_DIR) + "/config/maps/" + name;
}

TEST(TourRunTest, RingClosedAfterFiftyMetresWithoutFalseLoops) {
  Config config;
  config.simulator.route.clearance_m = 0.3;  // the route keeps 0.45 m from every obstacle
  const slam::MapRun run = slam::MapSimulation(config, ToursFile("tours/two_rings.yaml"),
                                               ToursFile("tours/two_rings_west.txt"), /*seed=*/1);
  const eval::TourEvaluation e = eval::EvaluateTour(run);
  std::printf("two_rings west ring: %s\n", eval::FormatTourEvaluation(e).c_str());
  ASSERT_GE(e.travel_m, 50.0);
  EXPECT_EQ(e.false_accepted, 0);
  EXPECT_GE(e.longest_loop_path_m, 45.0);  // the ring's closure itself was accepted
  EXPECT_LT(e.ate_m * 2.5, e.odometry_ate_m);
  EXPECT_LE(e.ate_m, 0.05);
  // An uncalibrated base: wall edges alone (landmarks.require_calibrated_base).
  EXPECT_EQ(e.landmarks, 0);
  EXPECT_GE(e.wall_edges, 50);
  EXPECT_LE(e.wall_rejected * 10, e.wall_edges);
  EXPECT_LE(e.wall_error_rms_m, 0.02);
  EXPECT_LE(e.wall_error_max_m, 0.06);
  // The loops are accurate, and their information does not claim more than they deliver
  // (the translation error is a length: sqrt(2) per-axis sigmas).
  EXPECT_GT(e.loop_sigma_mean_m, 0.0);
  EXPECT_LE(e.loop_error_rms_m, 0.01);
  EXPECT_LE(e.loop_error_rms_yaw_rad, 1.0 * M_PI / 180);
  EXPECT_LE(e.loop_error_rms_m, std::sqrt(2.0) * e.loop_sigma_mean_m);
  EXPECT_LE(e.loop_error_rms_yaw_rad, e.loop_sigma_mean_yaw_rad);
}

// Nothing on a tour observes the odometry's distance scale (a ring scaled by any factor still
// closes), so the map's scale is the base's: the simulated base over-reports its travel by
// 0.5 %, which alone costs about 5 cm on floor50's 87 m tour (uncalibrated: 6.31 cm on this
// seed, 5.5-6.7 cm over five). Calibrated once on another map's run with ground truth
// (`uwbsar calibrate`: seed_hall's 15 m loop), the tour keeps its scale and is within 5 cm.
// Measured (the gyro base, its file holding only the robot's keys): scale -0.00492 from the
// loop (truth -0.004975), that run's gyro bias -0.035 deg/s not written, ATE 0.66 cm.
/// `config` with the base's odometry calibration measured as `uwbsar calibrate` does, on another
/// map's run with ground truth (seed_hall's 15 m loop, seed 7), and applied as its file is:
/// only the robot's keys (a gyro base's bias belongs to the run and is not written).
Config CalibratedBase(Config config) {
  const slam::MapRun calibration_run =
      slam::MapSimulation(config, ToursFile("seed_hall/seed_hall.yaml"), "loop", /*seed=*/7);
  const CalibrationFit fit = testing::FitSimulatedRun(calibration_run, config.backend);
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

TEST(TourRunTest, ABaseCalibratedOnAnotherRunKeepsTheTourWithinFiveCentimetres) {
  Config plain;
  plain.simulator.route.clearance_m = 0.3;
  const Config config = CalibratedBase(plain);
  const double true_scale = 1.0 / (1.0 + config.simulator.odometry.wheel_scale_error) - 1.0;
  const slam::MapRun run = slam::MapSimulation(config, ToursFile("floor50/floor50.yaml"),
                                               ToursFile("floor50/route_tour.txt"), /*seed=*/1);
  const eval::TourEvaluation e = eval::EvaluateTour(run);
  std::printf("floor50 tour, calibrated base: %s\n", eval::FormatTourEvaluation(e).c_str());
  EXPECT_EQ(e.false_accepted, 0);
  EXPECT_TRUE(e.ring_closed);
  EXPECT_LE(e.ate_m, 0.05);
  // A calibrated base: its straight walls are landmarks, each observation on its wall's line.
  EXPECT_GE(e.landmarks, 5);
  EXPECT_LE(e.landmark_rejected * 10, e.landmark_observations);
  EXPECT_LE(e.landmark_error_rms_m, 0.02);
  EXPECT_LE(e.landmark_error_max_m, 0.06);
  const double scale = run.slam->graph().OdometryCalibrations().at(0)[kCalibScale];
  EXPECT_NEAR(scale, true_scale, 0.001);  // the tour did not move it away
}

/// Error of a localised run from its first fix on (what trajectory.tum holds), aligned.
double LocalizedError(const slam::LocalizeRun& run) {
  std::vector<std::pair<TimestampNs, Pose2>> from_fix;
  for (const auto& p : run.Trajectory(false)) {
    if (p.first >= run.first_fix_stamp_ns) from_fix.push_back(p);
  }
  return slam::TrajectoryError(from_fix, run.ground_truth).rmse_m;
}

// A map of hall_wing made with a calibrated base has its corridors' walls as landmarks. A second
// run through the building whose radar scene no longer matches the map's (another scene seed:
// each wall's scatterers drawn anew) finds few loops: it is placed after 12 m and lost for most
// of the tour. The map's walls, observed by the run's own straight walls, keep it on the
// corridors between the loops. Measured (seed 2): 50 of 90 keyframes observe a map wall; error
// from the first fix on 29.1 cm with them, 46.2 cm without.
TEST(TourRunTest, TheMapsWallsHoldARunLocalisedInItBetweenItsFewLoops) {
  Config plain;
  plain.simulator.route.clearance_m = 0.3;
  const Config config = CalibratedBase(plain);
  const std::string building = ToursFile("tours/hall_wing.yaml");
  const std::string route = ToursFile("tours/hall_wing_tour.txt");
  const slam::MapRun a = slam::MapSimulation(config, building, route, /*seed=*/1);
  const SessionData map = slam::CaptureSession(a);
  ASSERT_GE(map.landmarks.size(), 5u);
  Config no_walls = config;
  no_walls.place_recognition.wall_profiles.landmarks.enabled = false;
  const slam::LocalizeRun with = slam::LocalizeSimulation(map, config, building, route, 2, 2);
  const slam::LocalizeRun without = slam::LocalizeSimulation(map, no_walls, building, route, 2, 2);
  ASSERT_GE(with.first_fix, 0);
  ASSERT_EQ(with.keyframes.size(), without.keyframes.size());
  int observing = 0;
  for (const LocalizedKeyframe& k : with.keyframes) observing += k.walls > 0;
  for (const LocalizedKeyframe& k : without.keyframes) EXPECT_EQ(k.walls, 0);
  const double error_m = LocalizedError(with), error_without_m = LocalizedError(without);
  std::printf(
      "localised in hall_wing: %d of %zu keyframes observe map walls; error from the "
      "first fix %.2f cm (%.2f cm without the walls)\n",
      observing, with.keyframes.size(), error_m * 100, error_without_m * 100);
  EXPECT_GE(observing * 3, static_cast<int>(with.keyframes.size()));
  EXPECT_LE(error_m, 0.8 * error_without_m);
}

}  // namespace
}  // namespace uwbsar
