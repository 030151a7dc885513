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
// The second test maps floor50's tour with a base calibrated on another map's run (localisation in
// a tour's map: changed_building_test.cc).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <vector>

#include "eval/tour/tour_eval.h"
#include "slam/app_config.h"
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
TEST(TourRunTest, ABaseCalibratedOnAnotherRunKeepsTheTourWithinFiveCentimetres) {
  Config plain;
  plain.simulator.route.clearance_m = 0.3;
  const Config config = testing::CalibratedBase(plain);
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

}  // namespace
}  // namespace uwbsar
